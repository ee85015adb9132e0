// HDF5 + XDMF field output through the HDF5 C API. Every HDF5 id lives in a small RAII
// holder so an exception anywhere releases it; HDF5's own stderr error printing is switched
// off while we work and its error stack is turned into the exception message instead.
#include "core/output/field_writer.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <utility>

#include "core/fault_injection.hpp"
#include "core/output/hdf5_support.hpp"
#include "core/output/xml_escape.hpp"

namespace afemp::core {

static_assert(std::is_same_v<hid_t, std::int64_t>, "FieldWriter stores hid_t as int64_t");

namespace {

using hdf5::check;
using hdf5::fail;
using hdf5::Handle;
using hdf5::hdf5_reason;
using hdf5::QuietErrors;
using hdf5::unlocked_fapl;
using hdf5::untimed_plist;

void write_attribute(hid_t object, const char* name, hid_t file_type, hid_t mem_type,
                     const void* value, const std::string& path) {
  const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  if (!space.valid()) fail(path, std::string("cannot create dataspace for attribute ") + name);
  const Handle attr(H5Acreate2(object, name, file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                    H5Aclose);
  if (!attr.valid()) fail(path, std::string("cannot create attribute ") + name);
  check(H5Awrite(attr.get(), mem_type, value), path, std::string("cannot write attribute ") + name);
}

void write_string_attribute(hid_t object, const char* name, const std::string& value,
                            const std::string& path) {
  const Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (!type.valid()) fail(path, "cannot create string type");
  check(H5Tset_size(type.get(), value.size() + 1), path, "cannot size string type");
  check(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), path, "cannot set string padding");
  write_attribute(object, name, type.get(), type.get(), value.c_str(), path);
}

// An n x components dataset (rank 1 for one component) of file_type, from data in mem_type.
hid_t write_matrix(hid_t group, const std::string& name, std::size_t n, int components,
                   hid_t file_type, hid_t mem_type, const void* data, hid_t dcpl,
                   const std::string& path) {
  const hsize_t dims[2] = {static_cast<hsize_t>(n), static_cast<hsize_t>(components)};
  const int rank = components == 1 ? 1 : 2;
  const Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose);
  if (!space.valid()) fail(path, "cannot create dataspace for " + name);
  const hid_t dset =
      H5Dcreate2(group, name.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (dset < 0) fail(path, "cannot create dataset " + name);
  // One write per dataset, never per point; an empty block has nothing to write.
  if (n > 0 && H5Dwrite(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    const std::string reason = hdf5_reason();
    H5Dclose(dset);
    throw std::runtime_error(path + ": cannot write dataset " + name + ": " + reason);
  }
  return dset;
}

hid_t write_doubles(hid_t group, const std::string& name, std::size_t n, int components,
                    const double* data, hid_t dcpl, const std::string& path) {
  return write_matrix(group, name, n, components, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data, dcpl,
                      path);
}

std::string frame_name(std::size_t frame) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%06zu", frame);
  return buf;
}

// Shortest text that reads back to the same double: the index time equals the HDF5 one.
std::string format_double(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

const char* attribute_type(int components) {
  switch (components) {
    case 1:
      return "Scalar";
    case 3:
      return "Vector";
    case 6:
      return "Tensor6";
    case 9:
      return "Tensor";
    default:
      return "Matrix";
  }
}

// XDMF topology of a block by its nodes per cell (1: a point block).
const char* topology_type(int nodes_per_cell) {
  switch (nodes_per_cell) {
    case 1:
      return "Polyvertex";
    case 8:
      return "Hexahedron";
    default:
      return "Polyline";
  }
}

std::string dimensions(std::size_t n, int components) {
  return components == 1 ? std::to_string(n) : std::to_string(n) + " " + std::to_string(components);
}

// afemp order (xx, yy, zz, yz, xz, xy) -> XDMF Tensor6 order (xx, xy, xz, yy, yz, zz):
// XDMF component k is afemp component kTensor6FromAfemp[k].
constexpr int kTensor6FromAfemp[6] = {0, 5, 4, 1, 3, 2};
constexpr const char* kTensor6Order = "xx,xy,xz,yy,yz,zz";

// Returns an open file id; the caller owns it (wraps it in a Handle at once).
hid_t open_for_reading(const std::string& h5_path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(h5_path, ec))
    throw std::runtime_error(h5_path + ": no such file");
  const Handle fapl(unlocked_fapl(h5_path), H5Pclose);
  const hid_t file = H5Fopen(h5_path.c_str(), H5F_ACC_RDONLY, fapl.get());
  if (file < 0) fail(h5_path, "cannot open HDF5 file");
  return file;
}

[[noreturn]] void reject(const std::string& path, const std::string& what) {
  throw std::invalid_argument("FieldWriter::write_frame: " + path + ": " + what);
}

// A group or dataset name we create: HDF5 reads '/' as a path separator and "." as the
// group itself.
bool bad_name(const std::string& name) {
  return name.empty() || name == "." || name.find('/') != std::string::npos;
}

// Checks one group of fields (a block's node or cell fields) for n items; `what` names the
// group in messages, e.g. "block 'hexahedra': cell field".
void check_fields(std::span<const FieldView> fields, std::size_t n, const std::string& what,
                  const std::string& path) {
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const FieldView& f = fields[i];
    if (bad_name(f.name))
      reject(path, what + " '" + f.name + "': bad name (empty, \".\", or contains '/')");
    if (f.components < 1)
      reject(path, what + " '" + f.name + "' has " + std::to_string(f.components) + " components");
    if (n > 0 && f.data == nullptr) reject(path, what + " '" + f.name + "' has no data");
    const std::size_t expected = n * static_cast<std::size_t>(f.components);
    if (f.size != FieldView::unknown_size && f.size != expected)
      reject(path, what + " '" + f.name + "' has " + std::to_string(f.size) + " values, expected " +
                       std::to_string(n) + " x " + std::to_string(f.components) + " = " +
                       std::to_string(expected));
    for (std::size_t j = 0; j < i; ++j)
      if (fields[j].name == f.name) reject(path, what + " '" + f.name + "' given twice");
  }
}

// Writes a block's fields into a new subgroup (node or cell) of the block group; 6-component
// fields go through `scratch` to reorder them to XDMF Tensor6 order.
void write_fields(hid_t block, const char* subgroup, std::span<const FieldView> fields,
                  std::size_t n, hid_t gcpl, hid_t dcpl, std::vector<double>& scratch,
                  const std::string& path) {
  const Handle group(H5Gcreate2(block, subgroup, H5P_DEFAULT, gcpl, H5P_DEFAULT), H5Gclose);
  if (!group.valid()) fail(path, std::string("cannot create group ") + subgroup);
  const std::string where = path + "/" + subgroup;
  for (const FieldView& f : fields) {
    if (f.components == 6) {
      scratch.resize(n * 6);
      for (std::size_t i = 0; i < n; ++i)
        for (int k = 0; k < 6; ++k) scratch[i * 6 + k] = f.data[i * 6 + kTensor6FromAfemp[k]];
      const Handle dset(write_doubles(group.get(), f.name, n, 6, scratch.data(), dcpl, where),
                        H5Dclose);
      write_string_attribute(dset.get(), "component_order", kTensor6Order, where);
    } else {
      const Handle dset(write_doubles(group.get(), f.name, n, f.components, f.data, dcpl, where),
                        H5Dclose);
    }
  }
}

}  // namespace

FieldWriter::FieldWriter(std::string directory, std::string stem)
    : directory_(std::move(directory)), stem_(std::move(stem)) {
  if (stem_.empty() || stem_.find('/') != std::string::npos)
    throw std::invalid_argument("FieldWriter: stem '" + stem_ + "' must be a plain file name");
  const std::filesystem::path dir(directory_.empty() ? "." : directory_);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    throw std::runtime_error(dir.string() + ": cannot create output directory: " + ec.message());
  h5_path_ = (dir / (stem_ + ".h5")).string();
  xmf_path_ = (dir / (stem_ + ".xmf")).string();

  const QuietErrors quiet;
  const Handle fapl(unlocked_fapl(h5_path_), H5Pclose);
  file_ = H5Fcreate(h5_path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (file_ < 0) fail(h5_path_, "cannot create HDF5 file");
  try {
    write_index();  // an empty but valid index from the start
  } catch (...) {
    H5Fclose(static_cast<hid_t>(file_));
    throw;
  }
}

// The index text: one line per frame ("F time"), per block ("B npc points cells
// connectivity-frame name"), per node and cell field ("N components name", "C ..."), and per
// stored connectivity ("S frame kind block"); times in hexadecimal, exact.
std::string FieldWriter::index_text() const {
  std::string out;
  char buf[96];
  for (const FrameRecord& f : frames_) {
    std::snprintf(buf, sizeof buf, "F %a\n", f.time);
    out += buf;
    for (const BlockRecord& b : f.blocks) {
      std::snprintf(buf, sizeof buf, "B %d %zu %zu %zu ", b.nodes_per_cell, b.n_points, b.n_cells,
                    b.connectivity_frame);
      out += buf + b.name + "\n";
      for (const FieldRecord& r : b.node_fields)
        out += "N " + std::to_string(r.components) + " " + r.name + "\n";
      for (const FieldRecord& r : b.cell_fields)
        out += "C " + std::to_string(r.components) + " " + r.name + "\n";
    }
  }
  for (const StoredConnectivity& c : connectivity_)
    out += "S " + std::to_string(c.frame) + " " + std::to_string(static_cast<int>(c.kind)) + " " +
           c.block + "\n";
  return out;
}

FieldWriter::FieldWriter(std::string directory, std::string stem, const std::string& index)
    : directory_(std::move(directory)), stem_(std::move(stem)) {
  const std::filesystem::path dir(directory_.empty() ? "." : directory_);
  h5_path_ = (dir / (stem_ + ".h5")).string();
  xmf_path_ = (dir / (stem_ + ".xmf")).string();
  const auto bad = [&](const std::string& what) {
    throw std::runtime_error(h5_path_ + ": cannot continue the field series: " + what);
  };
  // The records.
  std::istringstream in(index);
  std::string line;
  std::vector<StoredConnectivity> stored;
  while (std::getline(in, line)) {
    if (line.size() < 2) bad("bad index line '" + line + "'");
    std::istringstream l(line.substr(2));
    const auto rest = [&] {
      std::string name;
      l >> std::ws;
      std::getline(l, name);
      return name;
    };
    if (line[0] == 'F') {
      std::string t;
      l >> t;
      frames_.push_back({std::strtod(t.c_str(), nullptr), {}});
    } else if (line[0] == 'B' && !frames_.empty()) {
      BlockRecord b;
      l >> b.nodes_per_cell >> b.n_points >> b.n_cells >> b.connectivity_frame;
      b.name = rest();
      frames_.back().blocks.push_back(std::move(b));
    } else if ((line[0] == 'N' || line[0] == 'C') && !frames_.empty() &&
               !frames_.back().blocks.empty()) {
      FieldRecord r;
      l >> r.components;
      r.name = rest();
      BlockRecord& b = frames_.back().blocks.back();
      (line[0] == 'N' ? b.node_fields : b.cell_fields).push_back(std::move(r));
    } else if (line[0] == 'S') {
      StoredConnectivity c;
      int kind = 0;
      l >> c.frame >> kind;
      c.kind = kind == 0 ? CellKind::hexahedron : CellKind::line;
      c.block = rest();
      stored.push_back(std::move(c));
    } else {
      bad("bad index line '" + line + "'");
    }
    if (!l && line[0] != 'F') bad("bad index line '" + line + "'");
  }

  const QuietErrors quiet;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(h5_path_, ec)) bad("no such file");
  // In place: the listed frames kept, later ones dropped. A file whose last write failed (a
  // full disk) or was cut off (a crash) may refuse that; the listed frames are then copied
  // into a fresh file that replaces it.
  std::string failure;
  if (!drop_frames_after(stored, failure)) {
    if (file_ >= 0) H5Fclose(static_cast<hid_t>(file_));
    file_ = -1;
    H5Eclear2(H5E_DEFAULT);
    copy_listed_frames(failure);
    if (!drop_frames_after(stored, failure)) {
      if (file_ >= 0) H5Fclose(static_cast<hid_t>(file_));
      file_ = -1;
      bad(failure);
    }
  }
  connectivity_ = std::move(stored);
  write_index();
}

// Opens the file for writing, checks the listed frames are there, deletes later ones and
// reads the stored connectivities; false with the reason when any of it fails.
bool FieldWriter::drop_frames_after(std::vector<StoredConnectivity>& stored, std::string& failure) {
  const Handle fapl(unlocked_fapl(h5_path_), H5Pclose);
  file_ = H5Fopen(h5_path_.c_str(), H5F_ACC_RDWR, fapl.get());
  if (file_ < 0) {
    failure = "cannot open it for writing (" + hdf5_reason() + ")";
    return false;
  }
  const hid_t file = static_cast<hid_t>(file_);
  for (std::size_t f = 0; f < frames_.size(); ++f)
    if (H5Lexists(file, frame_name(f).c_str(), H5P_DEFAULT) <= 0) {
      failure = "frame " + std::to_string(f) + " of the " + std::to_string(frames_.size()) +
                " the checkpoint lists is missing";
      return false;
    }
  for (std::size_t f = frames_.size();; ++f) {
    const std::string name = frame_name(f);
    if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0) break;
    if (H5Ldelete(file, name.c_str(), H5P_DEFAULT) < 0) {
      failure = "cannot drop " + name + " (" + hdf5_reason() + ")";
      return false;
    }
  }
  H5Eclear2(H5E_DEFAULT);
  for (StoredConnectivity& c : stored) {
    const std::string dataset = frame_name(c.frame) + "/" + c.block + "/connectivity";
    const Handle dset(H5Dopen2(file, dataset.c_str(), H5P_DEFAULT), H5Dclose);
    const Handle space(dset.valid() ? H5Dget_space(dset.get()) : -1, H5Sclose);
    const hssize_t count = space.valid() ? H5Sget_simple_extent_npoints(space.get()) : -1;
    c.cells.resize(count > 0 ? static_cast<std::size_t>(count) : 0);
    if (count < 0 || (!c.cells.empty() && H5Dread(dset.get(), H5T_NATIVE_INT32, H5S_ALL, H5S_ALL,
                                                  H5P_DEFAULT, c.cells.data()) < 0)) {
      failure = "cannot read " + dataset + " (" + hdf5_reason() + ")";
      return false;
    }
  }
  if (H5Fflush(file, H5F_SCOPE_LOCAL) < 0) {
    failure = "cannot flush (" + hdf5_reason() + ")";
    return false;
  }
  return true;
}

// Copies the frames the index lists into DIR/STEM.h5.rebuilt and renames it over the file.
void FieldWriter::copy_listed_frames(const std::string& why) {
  const auto bad = [&](const std::string& what) {
    throw std::runtime_error(h5_path_ + ": cannot continue the field series: " + why +
                             "; copying its frames into a new file failed too: " + what);
  };
  const std::string fresh = h5_path_ + ".rebuilt";
  {
    const Handle fapl(unlocked_fapl(h5_path_), H5Pclose);
    const Handle from(H5Fopen(h5_path_.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose);
    if (!from.valid()) bad("cannot open it (" + hdf5_reason() + ")");
    const Handle to(H5Fcreate(fresh.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
    if (!to.valid()) bad("cannot create " + fresh + " (" + hdf5_reason() + ")");
    for (std::size_t f = 0; f < frames_.size(); ++f) {
      const std::string name = frame_name(f);
      if (H5Ocopy(from.get(), name.c_str(), to.get(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT) < 0)
        bad("frame " + name + " (" + hdf5_reason() + ")");
    }
    if (H5Fflush(to.get(), H5F_SCOPE_LOCAL) < 0) bad("cannot flush " + fresh);
  }
  std::error_code ec;
  std::filesystem::rename(fresh, h5_path_, ec);
  if (ec) bad("cannot rename " + fresh + ": " + ec.message());
}

FieldWriter::~FieldWriter() {
  if (file_ >= 0) {
    const QuietErrors quiet;
    H5Fclose(static_cast<hid_t>(file_));
    H5Eclear2(H5E_DEFAULT);
  }
}

void FieldWriter::write_frame(double time, long step, std::size_t n_points, const double* positions,
                              std::span<const FieldView> fields) {
  const PointBlock particles[] = {{"particles", n_points, positions, fields}};
  write_frame(time, step, particles, {});
}

void FieldWriter::write_frame(double time, long step, std::span<const PointBlock> points,
                              std::span<const MeshBlock> meshes) {
  const std::size_t frame = frames_.size();
  const std::string group_name = frame_name(frame);

  // Check everything before touching the file so a bad call leaves no half frame behind.
  std::vector<const std::string*> names;
  auto check_block = [&](const std::string& name, std::size_t n, const void* positions) {
    if (bad_name(name))
      reject(h5_path_, "bad block name '" + name + "' (empty, \".\", or contains '/')");
    for (const std::string* seen : names)
      if (*seen == name) reject(h5_path_, "block '" + name + "' given twice");
    names.push_back(&name);
    if (n > 0 && positions == nullptr)
      reject(h5_path_,
             "block '" + name + "': positions are null for " + std::to_string(n) + " points");
  };
  auto records = [](std::span<const FieldView> views) {
    std::vector<FieldRecord> out;
    out.reserve(views.size());
    for (const FieldView& f : views) out.push_back({f.name, f.components});
    return out;
  };
  FrameRecord record{time, {}};
  record.blocks.reserve(points.size() + meshes.size());
  for (const PointBlock& b : points) {
    check_block(b.name, b.n_points, b.positions);
    check_fields(b.fields, b.n_points, "block '" + b.name + "': field", h5_path_);
    record.blocks.push_back({b.name, 1, b.n_points, b.n_points, frame, records(b.fields), {}});
  }
  // The frame whose group holds each mesh block's connectivity: this one, or the last one
  // that stored an equal connectivity for the block (contents compared, so the caller need
  // not say when it changes).
  std::vector<std::size_t> holder(meshes.size(), frame);
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    const MeshBlock& b = meshes[m];
    check_block(b.name, b.n_nodes, b.node_positions);
    if (b.n_cells > 0 && b.connectivity == nullptr)
      reject(h5_path_, "block '" + b.name + "': connectivity is null for " +
                           std::to_string(b.n_cells) + " cells");
    const std::size_t npc = static_cast<std::size_t>(nodes_per_cell(b.kind));
    const std::span<const std::int32_t> cells(b.connectivity, b.n_cells * npc);
    for (std::size_t i = 0; i < cells.size(); ++i)
      if (cells[i] < 0 || static_cast<std::size_t>(cells[i]) >= b.n_nodes)
        reject(h5_path_, "block '" + b.name + "': cell " + std::to_string(i / npc) +
                             " refers to node " + std::to_string(cells[i]) + " of " +
                             std::to_string(b.n_nodes));
    check_fields(b.node_fields, b.n_nodes, "block '" + b.name + "': node field", h5_path_);
    check_fields(b.cell_fields, b.n_cells, "block '" + b.name + "': cell field", h5_path_);
    for (const StoredConnectivity& s : connectivity_)
      if (s.block == b.name && s.kind == b.kind && std::ranges::equal(s.cells, cells))
        holder[m] = s.frame;
    record.blocks.push_back({b.name, static_cast<int>(npc), b.n_nodes, b.n_cells, holder[m],
                             records(b.node_fields), records(b.cell_fields)});
  }

  const QuietErrors quiet;
  const hid_t file = static_cast<hid_t>(file_);
  const std::string where = h5_path_ + ":/" + group_name;
  try {
    const Handle gcpl(untimed_plist(H5P_GROUP_CREATE, where), H5Pclose);
    const Handle dcpl(untimed_plist(H5P_DATASET_CREATE, where), H5Pclose);
    const Handle group(H5Gcreate2(file, group_name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT),
                       H5Gclose);
    if (!group.valid()) fail(where, "cannot create group");
    write_attribute(group.get(), "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &time, where);
    const std::int64_t step64 = step;
    write_attribute(group.get(), "step", H5T_STD_I64LE, H5T_NATIVE_INT64, &step64, where);

    // The block group with its topology name and positions; the caller adds the rest.
    auto open_block = [&](const std::string& name, int npc, std::size_t n,
                          const double* positions) {
      const std::string block_where = where + "/" + name;
      Handle block(H5Gcreate2(group.get(), name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT),
                   H5Gclose);
      if (!block.valid()) fail(block_where, "cannot create group");
      write_string_attribute(block.get(), "topology", topology_type(npc), block_where);
      const Handle position(
          write_doubles(block.get(), "position", n, 3, positions, dcpl.get(), block_where),
          H5Dclose);
      return block;
    };
    for (const PointBlock& b : points) {
      const Handle block = open_block(b.name, 1, b.n_points, b.positions);
      write_fields(block.get(), "node", b.fields, b.n_points, gcpl.get(), dcpl.get(), scratch_,
                   where + "/" + b.name);
    }
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const MeshBlock& b = meshes[m];
      const std::string block_where = where + "/" + b.name;
      const int npc = nodes_per_cell(b.kind);
      const Handle block = open_block(b.name, npc, b.n_nodes, b.node_positions);
      if (holder[m] != frame) {
        // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "/" + std::string&&.
        std::string target = "/";
        target.append(frame_name(holder[m])).append("/").append(b.name).append("/connectivity");
        check(H5Lcreate_soft(target.c_str(), block.get(), "connectivity", H5P_DEFAULT, H5P_DEFAULT),
              block_where, "cannot link connectivity to " + target);
      } else {
        const Handle conn(write_matrix(block.get(), "connectivity", b.n_cells, npc, H5T_STD_I32LE,
                                       H5T_NATIVE_INT32, b.connectivity, dcpl.get(), block_where),
                          H5Dclose);
      }
      write_fields(block.get(), "node", b.node_fields, b.n_nodes, gcpl.get(), dcpl.get(), scratch_,
                   block_where);
      write_fields(block.get(), "cell", b.cell_fields, b.n_cells, gcpl.get(), dcpl.get(), scratch_,
                   block_where);
    }
  } catch (...) {
    // Drop the half-written group so the next call can reuse the frame number.
    H5Ldelete(file, group_name.c_str(), H5P_DEFAULT);
    H5Eclear2(H5E_DEFAULT);
    throw;
  }
  fault_point("frame");
  // Data on disk before the index that points at it.
  check(H5Fflush(file, H5F_SCOPE_LOCAL), h5_path_, "cannot flush");
  for (std::size_t m = 0; m < meshes.size(); ++m) {
    if (holder[m] != frame) continue;
    const MeshBlock& b = meshes[m];
    const std::size_t count = b.n_cells * static_cast<std::size_t>(nodes_per_cell(b.kind));
    std::vector<std::int32_t> cells(b.connectivity, b.connectivity + count);
    const auto same_block = [&](const StoredConnectivity& s) { return s.block == b.name; };
    if (const auto it = std::ranges::find_if(connectivity_, same_block); it != connectivity_.end())
      *it = {b.name, frame, b.kind, std::move(cells)};
    else
      connectivity_.push_back({b.name, frame, b.kind, std::move(cells)});
  }
  frames_.push_back(std::move(record));
  write_index();
}

void FieldWriter::write_index() const {
  const std::string h5_name = xml_escape(stem_ + ".h5");
  std::string xml;
  xml.reserve(512 + frames_.size() * 1024);
  xml += "<?xml version=\"1.0\" ?>\n";
  xml += "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  // XDMF 2: ParaView's XDMF reader builds the implicit one-point cells of a Polyvertex
  // topology that has no connectivity DataItem.
  xml += "<Xdmf Version=\"2.0\">\n  <Domain>\n";
  xml += "    <Grid Name=\"" + xml_escape(stem_) +
         "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  // number_type: "Float" (the 8-byte doubles) or "Int" (the 4-byte connectivity).
  auto data_item = [&](std::size_t frame, const std::string& dataset, std::size_t n, int components,
                       const std::string& number_type) {
    return "<DataItem Dimensions=\"" + dimensions(n, components) + "\" NumberType=\"" +
           number_type + "\" Precision=\"" + (number_type == "Int" ? "4" : "8") +
           "\" Format=\"HDF\">" + h5_name + ":/" + frame_name(frame) + "/" + xml_escape(dataset) +
           "</DataItem>";
  };
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    const FrameRecord& fr = frames_[i];
    xml += "      <Grid Name=\"" + frame_name(i) +
           "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
    xml += "        <Time Value=\"" + format_double(fr.time) + "\"/>\n";
    for (const BlockRecord& b : fr.blocks) {
      const std::string block = b.name + "/";
      xml += "        <Grid Name=\"" + xml_escape(b.name) + "\" GridType=\"Uniform\">\n";
      xml += "          <Topology TopologyType=\"" + std::string(topology_type(b.nodes_per_cell)) +
             "\" NumberOfElements=\"" + std::to_string(b.n_cells) + "\"";
      if (b.nodes_per_cell == 1) {
        xml += " NodesPerElement=\"1\"/>\n";
      } else {
        if (b.nodes_per_cell == 2) xml += " NodesPerElement=\"2\"";
        xml += ">\n            " +
               data_item(b.connectivity_frame, block + "connectivity", b.n_cells, b.nodes_per_cell,
                         "Int") +
               "\n          </Topology>\n";
      }
      xml += "          <Geometry GeometryType=\"XYZ\">\n            " +
             data_item(i, block + "position", b.n_points, 3, "Float") + "\n          </Geometry>\n";
      auto attributes = [&](const std::vector<FieldRecord>& fields, const char* center,
                            const std::string& subgroup, std::size_t n) {
        for (const FieldRecord& f : fields)
          xml += "          <Attribute Name=\"" + xml_escape(f.name) + "\" AttributeType=\"" +
                 attribute_type(f.components) + "\" Center=\"" + center + "\">\n            " +
                 data_item(i, block + subgroup + f.name, n, f.components, "Float") +
                 "\n          </Attribute>\n";
      };
      attributes(b.node_fields, "Node", "node/", b.n_points);
      attributes(b.cell_fields, "Cell", "cell/", b.n_cells);
      xml += "        </Grid>\n";
    }
    xml += "      </Grid>\n";
  }
  xml += "    </Grid>\n  </Domain>\n</Xdmf>\n";

  // Write beside the index and rename over it: rename is atomic on POSIX, so a reader (or
  // a crash) only ever sees the old or the new index, never a torn one.
  const std::string tmp = xmf_path_ + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw std::runtime_error(tmp + ": cannot create XDMF index: " +
                               std::error_code(errno, std::generic_category()).message());
    out.write(xml.data(), static_cast<std::streamsize>(xml.size()));
    out.flush();
    if (!out) throw std::runtime_error(tmp + ": cannot write XDMF index");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, xmf_path_, ec);
  if (ec) throw std::runtime_error(xmf_path_ + ": cannot replace XDMF index: " + ec.message());
}

void skip_hdf5_exit_cleanup() {
  H5dont_atexit();
}

std::vector<double> read_dataset(const std::string& h5_path, const std::string& dataset,
                                 std::vector<std::size_t>* dims) {
  const QuietErrors quiet;
  const Handle file(open_for_reading(h5_path), H5Fclose);
  const std::string where = h5_path + ":" + dataset;
  const Handle dset(H5Dopen2(file.get(), dataset.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dset.valid()) fail(where, "cannot open dataset");
  const Handle space(H5Dget_space(dset.get()), H5Sclose);
  if (!space.valid()) fail(where, "cannot get dataspace");
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail(where, "cannot get rank");
  std::vector<hsize_t> extent(static_cast<std::size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space.get(), extent.data(), nullptr) < 0)
    fail(where, "cannot get dimensions");
  std::size_t total = 1;
  for (const hsize_t e : extent) total *= static_cast<std::size_t>(e);
  if (dims != nullptr) dims->assign(extent.begin(), extent.end());
  std::vector<double> values(total);
  if (total > 0)
    check(H5Dread(dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
          where, "cannot read dataset");
  return values;
}

namespace {
// An attribute of a group or dataset, opened for reading; `where` names it in errors.
Handle open_attribute(const Handle& file, const std::string& object_path, const std::string& name,
                      const std::string& where) {
  Handle attr(
      H5Aopen_by_name(file.get(), object_path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  if (!attr.valid()) fail(where, "cannot open attribute");
  return attr;
}
}  // namespace

double read_attribute(const std::string& h5_path, const std::string& object_path,
                      const std::string& name) {
  const QuietErrors quiet;
  const Handle file(open_for_reading(h5_path), H5Fclose);
  const std::string where = h5_path + ":" + object_path + "@" + name;
  const Handle attr = open_attribute(file, object_path, name, where);
  const Handle space(H5Aget_space(attr.get()), H5Sclose);
  if (!space.valid() || H5Sget_simple_extent_npoints(space.get()) != 1)
    throw std::runtime_error(where + ": attribute is not a single value");
  double value = 0.0;
  check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &value), where, "cannot read attribute");
  return value;
}

std::string read_string_attribute(const std::string& h5_path, const std::string& object_path,
                                  const std::string& name) {
  const QuietErrors quiet;
  const Handle file(open_for_reading(h5_path), H5Fclose);
  const std::string where = h5_path + ":" + object_path + "@" + name;
  const Handle attr = open_attribute(file, object_path, name, where);
  const Handle type(H5Aget_type(attr.get()), H5Tclose);
  if (!type.valid() || H5Tget_class(type.get()) != H5T_STRING ||
      H5Tis_variable_str(type.get()) != 0)
    throw std::runtime_error(where + ": attribute is not a fixed-length string");
  const std::size_t size = H5Tget_size(type.get());
  std::string buf(size, '\0');
  check(H5Aread(attr.get(), type.get(), buf.data()), where, "cannot read attribute");
  buf.resize(std::char_traits<char>::length(buf.c_str()));  // drop the terminator and padding
  return buf;
}

std::string read_link_target(const std::string& h5_path, const std::string& object_path) {
  const QuietErrors quiet;
  const Handle file(open_for_reading(h5_path), H5Fclose);
  const std::string where = h5_path + ":" + object_path;
  H5L_info_t info;
  check(H5Lget_info(file.get(), object_path.c_str(), &info, H5P_DEFAULT), where, "no such object");
  if (info.type != H5L_TYPE_SOFT) return {};
  std::string target(info.u.val_size, '\0');
  check(H5Lget_val(file.get(), object_path.c_str(), target.data(), target.size(), H5P_DEFAULT),
        where, "cannot read link");
  target.resize(std::char_traits<char>::length(target.c_str()));
  return target;
}

}  // namespace afemp::core
