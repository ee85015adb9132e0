// Small pieces every HDF5 user in core shares (core/output/field_writer.cpp,
// core/checkpoint.cpp): an owning holder for HDF5 ids, silenced automatic error printing, the
// error stack as a one-line reason, and the property lists we create files and objects with.
// Internal to the library (includes hdf5.h).
#pragma once

#include <hdf5.h>

#include <stdexcept>
#include <string>

namespace afemp::core::hdf5 {

// Owns one HDF5 id and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Handle& operator=(Handle&&) = delete;
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer close_;
};

// Silences HDF5's automatic error printing for the scope: we report through exceptions,
// and a library that writes stack dumps to stderr on a missing file is noise for callers.
class QuietErrors {
 public:
  QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

inline herr_t collect_innermost(unsigned, const H5E_error2_t* err, void* out) {
  // Walking downward, the last entry is the innermost: the most specific reason
  // (e.g. "unable to open file: ... errno = 13, error message = 'Permission denied'").
  if (err->desc != nullptr && err->desc[0] != '\0') *static_cast<std::string*>(out) = err->desc;
  return 0;
}

// The current HDF5 error stack, summarised in one line; clears the stack.
inline std::string hdf5_reason() {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_innermost, &reason);
  H5Eclear2(H5E_DEFAULT);
  // A failed system call's entry is a paragraph (time, file, descriptor, errno, "error message
  // = '...'", buffer, sizes); its system error text is the reason.
  const std::string key = "error message = '";
  if (const auto k = reason.find(key); k != std::string::npos) {
    const auto end = reason.find('\'', k + key.size());
    if (end != std::string::npos) reason = reason.substr(k + key.size(), end - k - key.size());
  }
  return reason.empty() ? std::string("HDF5 error") : reason;
}

[[noreturn]] inline void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error(path + ": " + what + ": " + hdf5_reason());
}

inline void check(herr_t status, const std::string& path, const std::string& what) {
  if (status < 0) fail(path, what);
}

// Object creation property list without modification times, so that the same calls give
// the same bytes (HDF5 stamps datasets with the wall clock by default).
inline hid_t untimed_plist(hid_t cls, const std::string& path) {
  const hid_t plist = H5Pcreate(cls);
  if (plist < 0) fail(path, "cannot create property list");
  if (H5Pset_obj_track_times(plist, false) < 0) {
    H5Pclose(plist);
    fail(path, "cannot disable time tracking");
  }
  return plist;
}

// File access without a lock: a viewer may open the file while the run goes on (it reads
// the frames the index lists, all flushed); the writer's default exclusive lock would make
// its open fail. The readers use it too, because HDF5 refuses to reopen a file in the same
// process with different locking flags.
inline hid_t unlocked_fapl(const std::string& path) {
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl < 0) fail(path, "cannot create file access property list");
#if H5_VERSION_GE(1, 10, 7)
  if (H5Pset_file_locking(fapl, false, true) < 0) {
    H5Pclose(fapl);
    fail(path, "cannot disable file locking");
  }
#endif
  return fapl;
}

}  // namespace afemp::core::hdf5
