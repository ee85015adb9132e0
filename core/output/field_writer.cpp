// HDF5 + XDMF field output through the HDF5 C API. Every HDF5 id lives in a small RAII
// holder so an exception anywhere releases it; HDF5's own stderr error printing is switched
// off while we work and its error stack is turned into the exception message instead.
#include "core/output/field_writer.hpp"

#include <hdf5.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <utility>

namespace afemp::core {

static_assert(std::is_same_v<hid_t, std::int64_t>, "FieldWriter stores hid_t as int64_t");

namespace {

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

herr_t collect_innermost(unsigned, const H5E_error2_t* err, void* out) {
  // Walking downward, the last entry is the innermost: the most specific reason
  // (e.g. "unable to open file: ... errno = 13, error message = 'Permission denied'").
  if (err->desc != nullptr && err->desc[0] != '\0') *static_cast<std::string*>(out) = err->desc;
  return 0;
}

// The current HDF5 error stack, summarised in one line; clears the stack.
std::string hdf5_reason() {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_innermost, &reason);
  H5Eclear2(H5E_DEFAULT);
  return reason.empty() ? std::string("HDF5 error") : reason;
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error(path + ": " + what + ": " + hdf5_reason());
}

void check(herr_t status, const std::string& path, const std::string& what) {
  if (status < 0) fail(path, what);
}

// Object creation property list without modification times, so that the same calls give
// the same bytes (HDF5 stamps datasets with the wall clock by default).
hid_t untimed_plist(hid_t cls, const std::string& path) {
  const hid_t plist = H5Pcreate(cls);
  if (plist < 0) fail(path, "cannot create property list");
  if (H5Pset_obj_track_times(plist, false) < 0) {
    H5Pclose(plist);
    fail(path, "cannot disable time tracking");
  }
  return plist;
}

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

hid_t write_matrix(hid_t group, const std::string& name, std::size_t n, int components,
                   const double* data, hid_t dcpl, const std::string& path) {
  const hsize_t dims[2] = {static_cast<hsize_t>(n), static_cast<hsize_t>(components)};
  const int rank = components == 1 ? 1 : 2;
  const Handle space(H5Screate_simple(rank, dims, nullptr), H5Sclose);
  if (!space.valid()) fail(path, "cannot create dataspace for " + name);
  const hid_t dset =
      H5Dcreate2(group, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, dcpl, H5P_DEFAULT);
  if (dset < 0) fail(path, "cannot create dataset " + name);
  // One write per dataset, never per point; an empty frame has nothing to write.
  if (n > 0 && H5Dwrite(dset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    const std::string reason = hdf5_reason();
    H5Dclose(dset);
    throw std::runtime_error(path + ": cannot write dataset " + name + ": " + reason);
  }
  return dset;
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

std::string xml_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

const char* attribute_type(int components) {
  switch (components) {
    case 1: return "Scalar";
    case 3: return "Vector";
    case 6: return "Tensor6";
    case 9: return "Tensor";
    default: return "Matrix";
  }
}

std::string dimensions(std::size_t n, int components) {
  return components == 1 ? std::to_string(n) : std::to_string(n) + " " + std::to_string(components);
}

// afemp order (xx, yy, zz, yz, xz, xy) -> XDMF Tensor6 order (xx, xy, xz, yy, yz, zz):
// XDMF component k is afemp component kTensor6FromAfemp[k].
constexpr int kTensor6FromAfemp[6] = {0, 5, 4, 1, 3, 2};
constexpr const char* kTensor6Order = "xx,xy,xz,yy,yz,zz";

// File access without a lock: a viewer may open the file while the run goes on (it reads
// the frames the index lists, all flushed); the writer's default exclusive lock would make
// its open fail. The readers use it too, because HDF5 refuses to reopen a file in the same
// process with different locking flags.
hid_t unlocked_fapl(const std::string& path) {
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

FieldWriter::~FieldWriter() {
  if (file_ >= 0) {
    const QuietErrors quiet;
    H5Fclose(static_cast<hid_t>(file_));
    H5Eclear2(H5E_DEFAULT);
  }
}

void FieldWriter::write_frame(double time, long step, std::size_t n_points,
                              const double* positions, std::span<const FieldView> fields) {
  // Check everything before touching the file so a bad call leaves no half frame behind.
  if (n_points > 0 && positions == nullptr)
    throw std::invalid_argument("FieldWriter::write_frame: positions is null for " +
                                std::to_string(n_points) + " points");
  FrameRecord record{time, n_points, {}};
  record.fields.reserve(fields.size());
  for (const FieldView& f : fields) {
    if (f.name.empty() || f.name.find('/') != std::string::npos || f.name == "." ||
        f.name == "position")
      throw std::invalid_argument("FieldWriter::write_frame: bad field name '" + f.name +
                                  "' (empty, contains '/', or reserved)");
    if (f.components < 1)
      throw std::invalid_argument("FieldWriter::write_frame: field '" + f.name + "' has " +
                                  std::to_string(f.components) + " components");
    if (n_points > 0 && f.data == nullptr)
      throw std::invalid_argument("FieldWriter::write_frame: field '" + f.name +
                                  "' has no data");
    for (const FieldRecord& seen : record.fields)
      if (seen.name == f.name)
        throw std::invalid_argument("FieldWriter::write_frame: field '" + f.name +
                                    "' given twice");
    record.fields.push_back({f.name, f.components});
  }

  const QuietErrors quiet;
  const hid_t file = static_cast<hid_t>(file_);
  const std::string group_name = frame_name(frames_.size());
  const std::string where = h5_path_ + ":/" + group_name;
  try {
    const Handle gcpl(untimed_plist(H5P_GROUP_CREATE, where), H5Pclose);
    const Handle dcpl(untimed_plist(H5P_DATASET_CREATE, where), H5Pclose);
    const Handle group(
        H5Gcreate2(file, group_name.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), H5Gclose);
    if (!group.valid()) fail(where, "cannot create group");
    write_attribute(group.get(), "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &time, where);
    const std::int64_t step64 = step;
    write_attribute(group.get(), "step", H5T_STD_I64LE, H5T_NATIVE_INT64, &step64, where);

    const Handle position(
        write_matrix(group.get(), "position", n_points, 3, positions, dcpl.get(), where),
        H5Dclose);
    for (const FieldView& f : fields) {
      if (f.components == 6) {
        scratch_.resize(n_points * 6);
        for (std::size_t i = 0; i < n_points; ++i)
          for (int k = 0; k < 6; ++k) scratch_[i * 6 + k] = f.data[i * 6 + kTensor6FromAfemp[k]];
        const Handle dset(
            write_matrix(group.get(), f.name, n_points, 6, scratch_.data(), dcpl.get(), where),
            H5Dclose);
        write_string_attribute(dset.get(), "component_order", kTensor6Order, where);
      } else {
        const Handle dset(
            write_matrix(group.get(), f.name, n_points, f.components, f.data, dcpl.get(), where),
            H5Dclose);
      }
    }
  } catch (...) {
    // Drop the half-written group so the next call can reuse the frame number.
    H5Ldelete(file, group_name.c_str(), H5P_DEFAULT);
    H5Eclear2(H5E_DEFAULT);
    throw;
  }
  // Data on disk before the index that points at it.
  check(H5Fflush(file, H5F_SCOPE_LOCAL), h5_path_, "cannot flush");
  frames_.push_back(std::move(record));
  write_index();
}

void FieldWriter::write_index() const {
  const std::string h5_name = xml_escape(stem_ + ".h5");
  std::string xml;
  xml.reserve(512 + frames_.size() * 512);
  xml += "<?xml version=\"1.0\" ?>\n";
  xml += "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  // XDMF 2: ParaView's XDMF reader builds the implicit one-point cells of a Polyvertex
  // topology that has no connectivity DataItem.
  xml += "<Xdmf Version=\"2.0\">\n  <Domain>\n";
  xml += "    <Grid Name=\"" + xml_escape(stem_) +
         "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    const FrameRecord& fr = frames_[i];
    const std::string group = frame_name(i);
    const std::string n = std::to_string(fr.n_points);
    auto data_item = [&](const std::string& dataset, int components) {
      return "<DataItem Dimensions=\"" + dimensions(fr.n_points, components) +
             "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" + h5_name + ":/" + group +
             "/" + xml_escape(dataset) + "</DataItem>";
    };
    xml += "      <Grid Name=\"" + group + "\" GridType=\"Uniform\">\n";
    xml += "        <Time Value=\"" + format_double(fr.time) + "\"/>\n";
    xml += "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + n +
           "\" NodesPerElement=\"1\"/>\n";
    xml += "        <Geometry GeometryType=\"XYZ\">\n          " + data_item("position", 3) +
           "\n        </Geometry>\n";
    for (const FieldRecord& f : fr.fields) {
      xml += "        <Attribute Name=\"" + xml_escape(f.name) + "\" AttributeType=\"" +
             attribute_type(f.components) + "\" Center=\"Node\">\n          " +
             data_item(f.name, f.components) + "\n        </Attribute>\n";
    }
    xml += "      </Grid>\n";
  }
  xml += "    </Grid>\n  </Domain>\n</Xdmf>\n";

  // Write beside the index and rename over it: rename is atomic on POSIX, so a reader (or
  // a crash) only ever sees the old or the new index, never a torn one.
  const std::string tmp = xmf_path_ + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(tmp + ": cannot create XDMF index: " +
                                       std::error_code(errno, std::generic_category()).message());
    out.write(xml.data(), static_cast<std::streamsize>(xml.size()));
    out.flush();
    if (!out) throw std::runtime_error(tmp + ": cannot write XDMF index");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, xmf_path_, ec);
  if (ec) throw std::runtime_error(xmf_path_ + ": cannot replace XDMF index: " + ec.message());
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
Handle open_attribute(const Handle& file, const std::string& object_path,
                      const std::string& name, const std::string& where) {
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

}  // namespace afemp::core
