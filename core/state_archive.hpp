// The whole state of a run in one HDF5 file, for checkpoints and restart (docs/restart.md).
// One function per part of the model visits its state through a StateArchive in both
// directions: writing, each item() stores the value under its name; reading, the same call
// fills the value from the file. Save and load thus cannot drift apart: a member added to the
// visit is saved and restored alike, and one left out shows in the restart test
// (tests/core/test_restart.cpp compares every field of a restarted run bit for bit).
//
// Arrays of doubles (and of Vec3, SymTensor, Mat3, std::array of doubles) are stored as
// n x k IEEE doubles, integers as their native integer types, so a checkpoint can be read with
// h5py or h5dump; other trivially copyable records are stored as their bytes. A checkpoint is
// read back by the afemp build that wrote it (the header names its version and layout).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "afemp/errors.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {

namespace state_detail {

enum class Scalar : std::uint8_t { f64, i8, u8, i32, u32, i64, u64, bytes };

// How an element of type T is stored: scalar type and components per element.
template <class T>
struct Layout {
  static constexpr Scalar scalar = Scalar::bytes;
  static constexpr std::size_t components = sizeof(T);
};
template <>
struct Layout<double> {
  static constexpr Scalar scalar = Scalar::f64;
  static constexpr std::size_t components = 1;
};
template <>
struct Layout<char> {
  static constexpr Scalar scalar = Scalar::i8;
  static constexpr std::size_t components = 1;
};
template <>
struct Layout<bool> {
  static constexpr Scalar scalar = Scalar::u8;
  static constexpr std::size_t components = 1;
};
template <>
struct Layout<std::uint8_t> {
  static constexpr Scalar scalar = Scalar::u8;
  static constexpr std::size_t components = 1;
};
template <>
struct Layout<std::int32_t> {
  static constexpr Scalar scalar = Scalar::i32;
  static constexpr std::size_t components = 1;
};
template <>
struct Layout<std::uint32_t> {
  static constexpr Scalar scalar = Scalar::u32;
  static constexpr std::size_t components = 1;
};
template <>
struct Layout<long> {
  static constexpr Scalar scalar = Scalar::i64;
  static constexpr std::size_t components = 1;
};
template <>
struct Layout<long long> {
  static constexpr Scalar scalar = Scalar::i64;
  static constexpr std::size_t components = 1;
};
template <>
struct Layout<unsigned long> {
  static constexpr Scalar scalar = Scalar::u64;
  static constexpr std::size_t components = 1;
};
template <>
struct Layout<unsigned long long> {
  static constexpr Scalar scalar = Scalar::u64;
  static constexpr std::size_t components = 1;
};
template <>
struct Layout<Vec3> {
  static constexpr Scalar scalar = Scalar::f64;
  static constexpr std::size_t components = 3;
};
template <>
struct Layout<SymTensor> {
  static constexpr Scalar scalar = Scalar::f64;
  static constexpr std::size_t components = 6;
};
template <>
struct Layout<Mat3> {
  static constexpr Scalar scalar = Scalar::f64;
  static constexpr std::size_t components = 9;
};
template <class T, std::size_t N>
struct Layout<std::array<T, N>> {
  static constexpr bool nested = Layout<T>::scalar != Scalar::bytes;
  static constexpr Scalar scalar = nested ? Layout<T>::scalar : Scalar::bytes;
  static constexpr std::size_t components = nested ? N * Layout<T>::components : sizeof(T) * N;
};

constexpr std::size_t scalar_size(Scalar s) {
  switch (s) {
    case Scalar::f64:
    case Scalar::i64:
    case Scalar::u64:
      return 8;
    case Scalar::i32:
    case Scalar::u32:
      return 4;
    default:
      return 1;
  }
}

}  // namespace state_detail

class StateArchive {
 public:
  enum class Mode { save, load };
  // save: creates `path` (replacing it); load: opens it for reading.
  StateArchive(std::string path, Mode mode);
  // In memory, no file (HDF5's core driver): an archive saved this way gives its bytes, the
  // file it would have written, with image(); one loaded reads such bytes. `name` stands for
  // the path in messages. (The whole state handed from rank to rank: core/time_loop.cpp.)
  struct InMemory {};
  StateArchive(std::string name, InMemory);
  StateArchive(std::string name, std::span<const std::byte> image);
  ~StateArchive();
  StateArchive(const StateArchive&) = delete;
  StateArchive& operator=(const StateArchive&) = delete;

  bool loading() const { return mode_ == Mode::load; }
  const std::string& path() const { return path_; }

  // Items between the construction and the destruction of a Group go into (come from) the
  // HDF5 group `name` below the current one.
  class Group {
   public:
    Group(StateArchive& archive, const std::string& name) : archive_(archive) {
      archive_.push_group(name);
    }
    ~Group() { archive_.pop_group(); }
    Group(const Group&) = delete;
    Group& operator=(const Group&) = delete;

   private:
    StateArchive& archive_;
  };

  // An array: stored whole; loading resizes it to the stored length.
  template <class T>
  void item(const char* name, std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>, "StateArchive stores plain values");
    using L = state_detail::Layout<T>;
    static_assert(sizeof(T) == L::components * state_detail::scalar_size(L::scalar));
    if (loading()) {
      values.resize(stored_count(name, L::scalar, L::components));
      read(name, values.data(), L::scalar, values.size() * L::components);
    } else {
      write(name, values.data(), L::scalar, values.size(), L::components);
    }
  }
  // std::vector<bool> is no array of values; those who use it go through a byte vector.
  void item(const char*, std::vector<bool>&) = delete;
  // One value (a number, a Vec3, a plain record).
  template <class T>
  void item(const char* name, T& value) {
    static_assert(std::is_trivially_copyable_v<T>, "StateArchive stores plain values");
    using L = state_detail::Layout<T>;
    if (loading()) {
      if (stored_count(name, L::scalar, L::components) != 1)
        fail(name, "holds an array where one value was expected");
      read(name, &value, L::scalar, L::components);
    } else {
      write(name, &value, L::scalar, 1, L::components);
    }
  }
  void item(const char* name, std::string& text);
  void item(const char* name, std::vector<std::string>& texts);
  // Arrays of arrays (per-thread lists, per-body lists): a count and one item per entry.
  template <class T>
  void item(const char* name, std::vector<std::vector<T>>& lists) {
    const Group group(*this, name);
    std::uint64_t n = lists.size();
    item("count", n);
    if (loading()) lists.assign(n, {});
    for (std::size_t i = 0; i < lists.size(); ++i) item(std::to_string(i).c_str(), lists[i]);
  }

  // Whether the current group holds `name` (for items a later version added).
  bool has(const char* name) const;
  // Saving: writes everything out and closes the file; throws CheckpointError on a write
  // error (a full disk). The destructor closes without checking.
  void close();
  // An in-memory save's bytes: writes everything out and closes it (as close()).
  std::vector<std::byte> image();
  // "file: /group/name" for messages.
  std::string where(const char* name) const;

 private:
  void push_group(const std::string& name);
  void pop_group();
  void close_groups();  // every group but the file's root
  void write(const char* name, const void* data, state_detail::Scalar scalar, std::size_t n,
             std::size_t components);
  std::size_t stored_count(const char* name, state_detail::Scalar scalar,
                           std::size_t components) const;
  void read(const char* name, void* data, state_detail::Scalar scalar, std::size_t values) const;
  [[noreturn]] void fail(const char* name, const std::string& what) const;

  std::string path_;
  Mode mode_;
  std::int64_t file_ = -1;            // hid_t
  std::vector<std::int64_t> groups_;  // open groups, innermost last
  std::vector<std::string> names_;    // their names
  bool in_memory_ = false;
};

}  // namespace afemp::core
