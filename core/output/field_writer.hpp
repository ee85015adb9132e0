// Field output: one HDF5 file per run (a group per frame, in it a group per block: particle
// clouds and hexahedron/line meshes) plus an XDMF index beside it, so ParaView opens
// DIR/STEM.xmf once and shows every block as a time series. The index is rewritten whole
// after every frame, so it stays valid (and lists every finished frame) if the run dies.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "afemp/tensor.hpp"

namespace afemp::core {

// One field of a block: data holds n * components contiguous doubles, item-major (item 0's
// components, then item 1's, ...), where n is the block's point, node or cell count.
//   components == 1: Scalar;  3: Vector (x, y, z);
//   6: symmetric tensor in afemp order (xx, yy, zz, yz, xz, xy); the file stores it in XDMF
//      Tensor6 order (xx, xy, xz, yy, yz, zz) and says so in the dataset attribute
//      "component_order";
//   9: full tensor, row-major (XDMF Tensor); any other count: XDMF Matrix (n x components).
// size is the number of doubles behind data where the caller knows it (the span helpers
// fill it in); write_frame then rejects a field whose length does not match its block.
// A Vec3 array and a SymTensor array are reinterpretable as 3 and 6 doubles per item
// (checked below); use as_doubles() or the helpers rather than casting by hand.
struct FieldView {
  static constexpr std::size_t unknown_size = static_cast<std::size_t>(-1);
  std::string name;  // the dataset name: not empty, not ".", no '/', unique in its group
  const double* data;
  int components;
  std::size_t size = unknown_size;
};

static_assert(sizeof(Vec3) == 3 * sizeof(double) && std::is_standard_layout_v<Vec3>,
              "a Vec3 array must be readable as 3 doubles per point");
static_assert(sizeof(SymTensor) == 6 * sizeof(double) && std::is_standard_layout_v<SymTensor>,
              "a SymTensor array must be readable as 6 doubles per point");

inline const double* as_doubles(const Vec3* v) {
  return reinterpret_cast<const double*>(v);
}
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
inline FieldView scalar_field(std::string name, std::span<const double> data) {
  return {std::move(name), data.data(), 1, data.size()};
}
inline FieldView vector_field(std::string name, std::span<const Vec3> data) {
  return {std::move(name), as_doubles(data.data()), 3, data.size() * 3};
}
inline FieldView tensor_field(std::string name, std::span<const SymTensor> data) {
  return {std::move(name), as_doubles(data.data()), 6, data.size() * 6};
}

// A cloud of points without connectivity (MPM particles): an XDMF Polyvertex grid.
struct PointBlock {
  std::string name;  // the group name, e.g. "particles": not empty, not ".", no '/'
  std::size_t n_points;
  const double* positions;            // n_points * 3 (may be null if n_points is 0)
  std::span<const FieldView> fields;  // one value (of components doubles) per point
};

// Cell shapes of a mesh block, with their node order:
//   hexahedron: 8 nodes, 0-3 round the bottom face and 4-7 round the top face, node 4 above
//               node 0 (fem/mesh.hpp's order, which is also XDMF's and VTK's);
//   line:       2 nodes (a truss or beam), written as an XDMF Polyline of 2 nodes per cell.
enum class CellKind { hexahedron, line };

// Nodes per cell of a kind: 8 or 2.
constexpr int nodes_per_cell(CellKind kind) {
  return kind == CellKind::hexahedron ? 8 : 2;
}

// An unstructured mesh of one cell kind (FE hexahedra, trusses) at the frame's time.
struct MeshBlock {
  std::string name;  // the group name, e.g. "hexahedra": not empty, not ".", no '/'
  CellKind kind;
  std::size_t n_nodes;
  const double* node_positions;  // current coordinates, n_nodes * 3
  std::size_t n_cells;
  const std::int32_t* connectivity;        // n_cells * nodes_per_cell(kind), 0-based into the nodes
  std::span<const FieldView> node_fields;  // one value per node
  std::span<const FieldView> cell_fields;  // one value per cell (eroded cells: a field, say)
};

// Writes DIR/STEM.h5 and DIR/STEM.xmf. File layout:
//   /frame_NNNNNN            group per frame (NNNNNN: the frame counter, 6 digits, from 0),
//                            attributes "time" (double) and "step" (64-bit integer)
//     <block>                group per block (PointBlock or MeshBlock name), with the string
//                            attribute "topology": "Polyvertex", "Hexahedron" or "Polyline"
//       position             n x 3 doubles: the points, or the mesh nodes
//       connectivity         meshes only: n_cells x 8 (or x 2) 32-bit integers, 0-based;
//                            written where it differs from the block's last stored one,
//                            else an HDF5 soft link to the frame that holds it (so every
//                            frame still reads whole, while storing it once)
//       node/<field>         n (1 component) or n x components doubles, one per point/node
//       cell/<field>         meshes only: the same, one per cell
// Numbers are IEEE little endian; 6-component fields carry the string attribute
// "component_order". The .xmf lists, for every frame, a spatial collection of one grid per
// block, inside a temporal collection; a frame that links its connectivity points the
// XDMF at the frame that stores it.
// Output is deterministic: the same calls give the same bytes (no timestamps in the file).
// The file is not locked, so ParaView can open the .xmf while the run is still writing.
// Not thread-safe (serial HDF5): call from one thread.
class FieldWriter {
 public:
  // Creates the directory (and parents) and truncates both files. Throws std::runtime_error
  // naming the path and the reason if either cannot be created.
  explicit FieldWriter(std::string directory, std::string stem = "fields");
  // Continues the series of an earlier run (a restart): opens DIR/STEM.h5 for writing, keeps
  // the frames `index` lists (index_text() of the writer then), drops any later ones (written
  // after the checkpoint) and rewrites the XDMF index. Throws std::runtime_error naming the
  // file when it cannot be opened or lacks a listed frame.
  FieldWriter(std::string directory, std::string stem, const std::string& index);
  ~FieldWriter();
  FieldWriter(const FieldWriter&) = delete;
  FieldWriter& operator=(const FieldWriter&) = delete;

  // Appends frame frames() with the given blocks (block names unique within the frame; a
  // block may be absent from some frames). Every input is checked before the file is
  // touched, so a bad call leaves no half frame. Flushes the HDF5 file, then replaces the
  // .xmf (temp file + rename). Throws std::invalid_argument for a bad name, component
  // count, field length or connectivity index, std::runtime_error if HDF5 or the file
  // system fails.
  void write_frame(double time, long step, std::span<const PointBlock> points,
                   std::span<const MeshBlock> meshes);
  // A frame of one point block named "particles".
  void write_frame(double time, long step, std::size_t n_points, const double* positions,
                   std::span<const FieldView> fields);

  std::size_t frames() const { return frames_.size(); }
  // What a restart needs to continue the series: the frames written so far, as text.
  std::string index_text() const;
  const std::string& h5_path() const { return h5_path_; }
  const std::string& xmf_path() const { return xmf_path_; }

 private:
  struct FieldRecord {
    std::string name;
    int components;
  };
  struct BlockRecord {
    std::string name;
    int nodes_per_cell;              // 1 for a point block (Polyvertex)
    std::size_t n_points;            // points, or mesh nodes
    std::size_t n_cells;             // n_points for a point block
    std::size_t connectivity_frame;  // the frame whose group stores the connectivity
    std::vector<FieldRecord> node_fields, cell_fields;
  };
  struct FrameRecord {
    double time;
    std::vector<BlockRecord> blocks;
  };
  // A mesh block's last stored connectivity, compared with each new frame's.
  struct StoredConnectivity {
    std::string block;
    std::size_t frame;
    CellKind kind;
    std::vector<std::int32_t> cells;
  };

  void write_index() const;
  bool drop_frames_after(std::vector<StoredConnectivity>& stored, std::string& failure);
  void copy_listed_frames(const std::string& why);

  std::string directory_;
  std::string stem_;
  std::string h5_path_;
  std::string xmf_path_;
  std::int64_t file_ = -1;  // hid_t (int64_t in HDF5 >= 1.10), kept out of this header
  std::vector<FrameRecord> frames_;
  std::vector<StoredConnectivity> connectivity_;  // one per mesh block name seen
  std::vector<double> scratch_;                   // reordered tensor copy, reused between frames
};

// Readers for tests and tools. Throw std::runtime_error naming the file and object when
// something is missing.
// The whole dataset as doubles in row-major order; dims (if given) receives its shape.
// For a program's main(), before any HDF5 call: the process ends without HDF5's exit-time
// cleanup, which (HDF5 1.10) crashes on a file whose writes failed (a full disk) and would turn
// a reported output error into a segmentation fault; the operating system closes the files.
void skip_hdf5_exit_cleanup();

std::vector<double> read_dataset(const std::string& h5_path, const std::string& dataset,
                                 std::vector<std::size_t>* dims = nullptr);
// A numeric scalar attribute of a group or dataset (integers are converted to double).
double read_attribute(const std::string& h5_path, const std::string& object_path,
                      const std::string& name);
// A string attribute (e.g. "component_order").
std::string read_string_attribute(const std::string& h5_path, const std::string& object_path,
                                  const std::string& name);
// Where the soft link object_path points (e.g. "/frame_000000/hexahedra/connectivity"), or
// an empty string if object_path is stored there.
std::string read_link_target(const std::string& h5_path, const std::string& object_path);

}  // namespace afemp::core
