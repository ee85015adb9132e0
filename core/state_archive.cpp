// The HDF5 side of core/state_archive.hpp: one dataset per item, n x k of the item's scalar
// type, in nested groups.
#include "core/state_archive.hpp"

#include <hdf5.h>

#include <cstring>
#include <filesystem>

#include "core/output/hdf5_support.hpp"

namespace afemp::core {

using hdf5::Handle;
using hdf5::QuietErrors;
using state_detail::Scalar;

namespace {

hid_t native_type(Scalar s) {
  switch (s) {
    case Scalar::f64:
      return H5T_NATIVE_DOUBLE;
    case Scalar::i8:
      return H5T_NATIVE_SCHAR;
    case Scalar::u8:
      return H5T_NATIVE_UINT8;
    case Scalar::i32:
      return H5T_NATIVE_INT32;
    case Scalar::u32:
      return H5T_NATIVE_UINT32;
    case Scalar::i64:
      return H5T_NATIVE_INT64;
    case Scalar::u64:
      return H5T_NATIVE_UINT64;
    case Scalar::bytes:
      return H5T_NATIVE_UINT8;
  }
  return H5T_NATIVE_UINT8;
}

hid_t file_type(Scalar s) {
  switch (s) {
    case Scalar::f64:
      return H5T_IEEE_F64LE;
    case Scalar::i8:
      return H5T_STD_I8LE;
    case Scalar::u8:
      return H5T_STD_U8LE;
    case Scalar::i32:
      return H5T_STD_I32LE;
    case Scalar::u32:
      return H5T_STD_U32LE;
    case Scalar::i64:
      return H5T_STD_I64LE;
    case Scalar::u64:
      return H5T_STD_U64LE;
    case Scalar::bytes:
      return H5T_STD_U8LE;
  }
  return H5T_STD_U8LE;
}

}  // namespace

StateArchive::StateArchive(std::string path, Mode mode) : path_(std::move(path)), mode_(mode) {
  const QuietErrors quiet;
  const Handle fapl(hdf5::unlocked_fapl(path_), H5Pclose);
  if (mode_ == Mode::save) {
    file_ = H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
    if (file_ < 0)
      throw CheckpointError(path_ + ": cannot create checkpoint: " + hdf5::hdf5_reason());
  } else {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path_, ec))
      throw CheckpointError(path_ + ": no such checkpoint file");
    file_ = H5Fopen(path_.c_str(), H5F_ACC_RDONLY, fapl.get());
    if (file_ < 0)
      throw CheckpointError(path_ + ": cannot open checkpoint: " + hdf5::hdf5_reason());
  }
  groups_.push_back(file_);
  names_.push_back("");
}

namespace {

// The core driver's file access, nothing written to disk.
Handle memory_fapl(const std::string& name) {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  if (fapl.get() < 0 || H5Pset_fapl_core(fapl.get(), std::size_t{1} << 20, false) < 0)
    throw CheckpointError(name + ": cannot set up an in-memory archive: " + hdf5::hdf5_reason());
  return fapl;
}

}  // namespace

StateArchive::StateArchive(std::string name, InMemory)
    : path_(std::move(name)), mode_(Mode::save), in_memory_(true) {
  const QuietErrors quiet;
  const Handle fapl = memory_fapl(path_);
  file_ = H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (file_ < 0) throw CheckpointError(path_ + ": cannot create in memory: " + hdf5::hdf5_reason());
  groups_.push_back(file_);
  names_.push_back("");
}

StateArchive::StateArchive(std::string name, std::span<const std::byte> image)
    : path_(std::move(name)), mode_(Mode::load), in_memory_(true) {
  const QuietErrors quiet;
  const Handle fapl = memory_fapl(path_);
  // The image is copied into the driver's own buffer (the default flags).
  if (H5Pset_file_image(fapl.get(), const_cast<std::byte*>(image.data()), image.size()) < 0)
    throw CheckpointError(path_ + ": cannot take its image: " + hdf5::hdf5_reason());
  file_ = H5Fopen(path_.c_str(), H5F_ACC_RDONLY, fapl.get());
  if (file_ < 0) throw CheckpointError(path_ + ": cannot open its image: " + hdf5::hdf5_reason());
  groups_.push_back(file_);
  names_.push_back("");
}

std::vector<std::byte> StateArchive::image() {
  if (!in_memory_ || mode_ != Mode::save || file_ < 0)
    throw std::logic_error("StateArchive::image: an open in-memory save only");
  const QuietErrors quiet;
  close_groups();
  std::vector<std::byte> bytes;
  ssize_t n = H5Fflush(file_, H5F_SCOPE_LOCAL) < 0 ? -1 : H5Fget_file_image(file_, nullptr, 0);
  if (n >= 0) {
    bytes.resize(static_cast<std::size_t>(n));
    n = H5Fget_file_image(file_, bytes.data(), bytes.size());
  }
  const std::string reason = n < 0 ? hdf5::hdf5_reason() : std::string();
  H5Fclose(static_cast<hid_t>(file_));
  file_ = -1;
  groups_.clear();
  if (n < 0) throw CheckpointError(path_ + ": cannot take its image: " + reason);
  return bytes;
}

StateArchive::~StateArchive() {
  const QuietErrors quiet;
  for (std::size_t g = groups_.size(); g-- > 1;) H5Gclose(static_cast<hid_t>(groups_[g]));
  if (file_ >= 0) H5Fclose(static_cast<hid_t>(file_));
  H5Eclear2(H5E_DEFAULT);
}

void StateArchive::close() {
  if (file_ < 0) return;
  const QuietErrors quiet;
  close_groups();
  const herr_t flushed = mode_ == Mode::save ? H5Fflush(file_, H5F_SCOPE_LOCAL) : 0;
  // The flush's reason (a full disk) before the close clears the error stack: a close after a
  // failed flush fails too, with an internal error of the metadata cache that says nothing.
  const std::string flush_reason = flushed < 0 ? hdf5::hdf5_reason() : std::string();
  const herr_t closed = H5Fclose(static_cast<hid_t>(file_));
  file_ = -1;
  groups_.clear();
  if (flushed < 0 || closed < 0)
    throw CheckpointError(
        path_ + ": cannot write checkpoint: " + (flushed < 0 ? flush_reason : hdf5::hdf5_reason()));
}

void StateArchive::close_groups() {
  for (std::size_t g = groups_.size(); g-- > 1;) H5Gclose(static_cast<hid_t>(groups_[g]));
  groups_.resize(1);
  names_.resize(1);
}

std::string StateArchive::where(const char* name) const {
  std::string w = path_ + ": ";
  for (std::size_t g = 1; g < names_.size(); ++g) w += "/" + names_[g];
  return w + "/" + name;
}

void StateArchive::fail(const char* name, const std::string& what) const {
  throw CheckpointError(where(name) + ": " + what);
}

void StateArchive::push_group(const std::string& name) {
  const QuietErrors quiet;
  const hid_t parent = static_cast<hid_t>(groups_.back());
  hid_t g;
  if (loading()) {
    g = H5Gopen2(parent, name.c_str(), H5P_DEFAULT);
    if (g < 0)
      fail(name.c_str(), "missing (written by another afemp version, or not a checkpoint)");
  } else {
    const Handle gcpl(hdf5::untimed_plist(H5P_GROUP_CREATE, path_), H5Pclose);
    g = H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT);
    if (g < 0) fail(name.c_str(), "cannot create group: " + hdf5::hdf5_reason());
  }
  groups_.push_back(g);
  names_.push_back(name);
}

void StateArchive::pop_group() {
  if (groups_.size() <= 1) return;
  H5Gclose(static_cast<hid_t>(groups_.back()));
  groups_.pop_back();
  names_.pop_back();
}

bool StateArchive::has(const char* name) const {
  const QuietErrors quiet;
  const htri_t exists = H5Lexists(static_cast<hid_t>(groups_.back()), name, H5P_DEFAULT);
  H5Eclear2(H5E_DEFAULT);
  return exists > 0;
}

void StateArchive::write(const char* name, const void* data, Scalar scalar, std::size_t n,
                         std::size_t components) {
  const QuietErrors quiet;
  const hsize_t dims[2] = {static_cast<hsize_t>(n), static_cast<hsize_t>(components)};
  const Handle space(H5Screate_simple(2, dims, nullptr), H5Sclose);
  const Handle dcpl(hdf5::untimed_plist(H5P_DATASET_CREATE, path_), H5Pclose);
  const Handle dset(H5Dcreate2(static_cast<hid_t>(groups_.back()), name, file_type(scalar),
                               space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
                    H5Dclose);
  if (!dset.valid()) fail(name, "cannot create dataset: " + hdf5::hdf5_reason());
  if (n > 0 && H5Dwrite(dset.get(), native_type(scalar), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail(name, "cannot write: " + hdf5::hdf5_reason());
}

std::size_t StateArchive::stored_count(const char* name, Scalar scalar,
                                       std::size_t components) const {
  const QuietErrors quiet;
  const Handle dset(H5Dopen2(static_cast<hid_t>(groups_.back()), name, H5P_DEFAULT), H5Dclose);
  if (!dset.valid()) fail(name, "missing (written by another afemp version, or another scene)");
  const Handle space(H5Dget_space(dset.get()), H5Sclose);
  hsize_t dims[2] = {0, 0};
  if (H5Sget_simple_extent_ndims(space.get()) != 2 ||
      H5Sget_simple_extent_dims(space.get(), dims, nullptr) < 0)
    fail(name, "is not an n x k array");
  const Handle type(H5Dget_type(dset.get()), H5Tclose);
  const bool same_kind = H5Tget_size(type.get()) == state_detail::scalar_size(scalar) &&
                         (H5Tget_class(type.get()) == H5T_FLOAT) == (scalar == Scalar::f64);
  if (!same_kind || dims[1] != components)
    fail(name, "is stored with " + std::to_string(dims[1]) + " components of " +
                   std::to_string(H5Tget_size(type.get())) + " bytes, this build expects " +
                   std::to_string(components) + " of " +
                   std::to_string(state_detail::scalar_size(scalar)) +
                   " (a checkpoint of another afemp version)");
  return static_cast<std::size_t>(dims[0]);
}

void StateArchive::read(const char* name, void* data, Scalar scalar, std::size_t values) const {
  if (values == 0) return;
  const QuietErrors quiet;
  const Handle dset(H5Dopen2(static_cast<hid_t>(groups_.back()), name, H5P_DEFAULT), H5Dclose);
  if (!dset.valid() ||
      H5Dread(dset.get(), native_type(scalar), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail(name, "cannot read: " + hdf5::hdf5_reason());
}

void StateArchive::item(const char* name, std::string& text) {
  std::vector<char> bytes(text.begin(), text.end());
  item(name, bytes);
  if (loading()) text.assign(bytes.begin(), bytes.end());
}

void StateArchive::item(const char* name, std::vector<std::string>& texts) {
  // All texts end to end, and their lengths.
  std::vector<char> bytes;
  std::vector<std::uint64_t> lengths;
  for (const std::string& t : texts) {
    bytes.insert(bytes.end(), t.begin(), t.end());
    lengths.push_back(t.size());
  }
  const Group group(*this, name);
  item("text", bytes);
  item("length", lengths);
  if (!loading()) return;
  texts.clear();
  std::size_t at = 0;
  for (const std::uint64_t n : lengths) {
    if (at + n > bytes.size()) fail(name, "lengths exceed the stored text");
    texts.emplace_back(bytes.data() + at, n);
    at += n;
  }
}

}  // namespace afemp::core
