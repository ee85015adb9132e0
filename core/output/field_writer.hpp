// Field output: one HDF5 file per run (a group per frame) plus an XDMF index beside it, so
// ParaView opens DIR/STEM.xmf directly as a time series. The index is rewritten whole after
// every frame, so it stays valid (and lists every finished frame) if the run dies later.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/tensor.hpp"

namespace afemp::core {

// One per-point field: data holds n_points * components contiguous doubles, point-major
// (point 0's components, then point 1's, ...).
//   components == 1: Scalar;  3: Vector (x, y, z);
//   6: symmetric tensor in afemp order (xx, yy, zz, yz, xz, xy); the file stores it in XDMF
//      Tensor6 order (xx, xy, xz, yy, yz, zz) and says so in the dataset attribute
//      "component_order";
//   9: full tensor, row-major (XDMF Tensor); any other count: XDMF Matrix (n x components).
// A Vec3 array and a SymTensor array are reinterpretable as 3 and 6 doubles per point
// (checked below); use as_doubles() rather than casting by hand.
struct FieldView {
  std::string name;  // the dataset name: not empty, no '/', not "position", unique per frame
  const double* data;
  int components;
};

static_assert(sizeof(Vec3) == 3 * sizeof(double) && std::is_standard_layout_v<Vec3>,
              "a Vec3 array must be readable as 3 doubles per point");
static_assert(sizeof(SymTensor) == 6 * sizeof(double) && std::is_standard_layout_v<SymTensor>,
              "a SymTensor array must be readable as 6 doubles per point");

inline const double* as_doubles(const Vec3* v) { return reinterpret_cast<const double*>(v); }
inline const double* as_doubles(const SymTensor* t) {
  return reinterpret_cast<const double*>(t);
}
inline FieldView scalar_field(std::string name, const double* data) {
  return {std::move(name), data, 1};
}
inline FieldView vector_field(std::string name, const Vec3* data) {
  return {std::move(name), as_doubles(data), 3};
}
inline FieldView tensor_field(std::string name, const SymTensor* data) {
  return {std::move(name), as_doubles(data), 6};
}

// Writes DIR/STEM.h5 and DIR/STEM.xmf. File layout:
//   /frame_NNNNNN          group per frame (NNNNNN: the frame counter, 6 digits, from 0),
//                          attributes "time" (double) and "step" (64-bit integer)
//     position             n x 3 doubles
//     <field>              n (1 component) or n x components doubles, IEEE little endian;
//                          6-component fields carry the string attribute "component_order"
// Output is deterministic: the same calls give the same bytes (no timestamps in the file).
// The file is not locked, so ParaView can open the .xmf while the run is still writing.
// Not thread-safe (serial HDF5): call from one thread.
class FieldWriter {
 public:
  // Creates the directory (and parents) and truncates both files. Throws std::runtime_error
  // naming the path and the reason if either cannot be created.
  explicit FieldWriter(std::string directory, std::string stem = "particles");
  ~FieldWriter();
  FieldWriter(const FieldWriter&) = delete;
  FieldWriter& operator=(const FieldWriter&) = delete;

  // Appends frame frames(): positions holds n_points * 3 doubles (may be null if n_points
  // is 0). Flushes the HDF5 file, then replaces the .xmf (temp file + rename). Throws
  // std::invalid_argument for a bad field name / component count, std::runtime_error if
  // HDF5 or the file system fails.
  void write_frame(double time, long step, std::size_t n_points, const double* positions,
                   std::span<const FieldView> fields);

  std::size_t frames() const { return frames_.size(); }
  const std::string& h5_path() const { return h5_path_; }
  const std::string& xmf_path() const { return xmf_path_; }

 private:
  struct FieldRecord {
    std::string name;
    int components;
  };
  struct FrameRecord {
    double time;
    std::size_t n_points;
    std::vector<FieldRecord> fields;
  };

  void write_index() const;

  std::string directory_;
  std::string stem_;
  std::string h5_path_;
  std::string xmf_path_;
  std::int64_t file_ = -1;  // hid_t (int64_t in HDF5 >= 1.10), kept out of this header
  std::vector<FrameRecord> frames_;
  std::vector<double> scratch_;  // reordered tensor copy, reused between frames
};

// Readers for tests and tools. Throw std::runtime_error naming the file and object when
// something is missing.
// The whole dataset as doubles in row-major order; dims (if given) receives its shape.
std::vector<double> read_dataset(const std::string& h5_path, const std::string& dataset,
                                 std::vector<std::size_t>* dims = nullptr);
// A numeric scalar attribute of a group or dataset (integers are converted to double).
double read_attribute(const std::string& h5_path, const std::string& object_path,
                      const std::string& name);
// A string attribute (e.g. "component_order").
std::string read_string_attribute(const std::string& h5_path, const std::string& object_path,
                                  const std::string& name);

}  // namespace afemp::core
