// FieldWriter: every dataset and attribute of every block (particles, hexahedra, trusses)
// reads back bit for bit, tensors come back in the documented XDMF order, an unchanged mesh
// connectivity is stored once, and the .xmf index is well-formed after every frame (crash
// safety). Files go to a per-test temporary directory that is removed afterwards.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "afemp/tensor.hpp"
#include "core/output/field_writer.hpp"
#include "scratch_dir.hpp"

namespace afemp::core {
namespace {

namespace fs = std::filesystem;

using TempDir = afemp::test::ScratchDir;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t pos = text.find(what); pos != std::string::npos;
       pos = text.find(what, pos + what.size()))
    ++n;
  return n;
}

// The first well-formedness problem of an XML text (empty if none): every element closed in
// order, one root element, quoted attribute values, no stray '<' or '>' in text. Enough to
// catch a torn or mis-nested index without depending on an XML library.
std::string xml_problem(const std::string& text) {
  std::vector<std::string> open;
  std::size_t roots = 0;
  std::size_t pos = 0;
  while (true) {
    const std::size_t lt = text.find('<', pos);
    const std::string between = text.substr(pos, lt == std::string::npos ? lt : lt - pos);
    if (between.find('>') != std::string::npos) return "stray '>' at " + std::to_string(pos);
    if (lt == std::string::npos) break;
    const std::size_t gt = text.find('>', lt);
    if (gt == std::string::npos) return "unterminated tag at " + std::to_string(lt);
    const std::string tag = text.substr(lt + 1, gt - lt - 1);
    pos = gt + 1;
    if (tag.find('<') != std::string::npos) return "'<' inside tag at " + std::to_string(lt);
    if (count(tag, "\"") % 2 != 0) return "unbalanced quotes in <" + tag + ">";
    if (tag.starts_with("?") || tag.starts_with("!")) continue;  // declaration, doctype
    if (tag.starts_with("/")) {
      const std::string name = tag.substr(1);
      if (open.empty() || open.back() != name) return "unexpected </" + name + ">";
      open.pop_back();
      continue;
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
    if (name.empty()) return "empty tag name at " + std::to_string(lt);
    if (open.empty() && ++roots > 1) return "second root element <" + name + ">";
    if (!tag.ends_with("/")) open.push_back(name);
  }
  if (!open.empty()) return "<" + open.back() + "> not closed";
  return roots == 1 ? "" : "no root element";
}

constexpr std::size_t kPoints = 5;

// Frame f's data: distinct, non-round values so a swapped component or frame shows.
struct FrameData {
  std::vector<Vec3> position, velocity;
  std::vector<double> pressure;
  std::vector<SymTensor> stress;
  explicit FrameData(int f) {
    for (std::size_t i = 0; i < kPoints; ++i) {
      const double b = static_cast<double>(i) + 0.1 * f;
      position.push_back({b / 3.0, -b / 7.0, b * 1e-3 + 0.5});
      velocity.push_back({1.0 / (b + 1.0), 2.5e2 * b, -b * b});
      pressure.push_back(std::exp(b) - 3.0);
      stress.push_back({11.0 + b, 22.0 + b, 33.0 + b, 23.0 + b, 13.0 + b, 12.0 + b});
    }
  }
  std::vector<FieldView> fields() const {
    return {scalar_field("pressure", pressure.data()), vector_field("velocity", velocity.data()),
            tensor_field("stress", stress.data())};
  }
  void write(FieldWriter& w, double time, long step) const {
    const auto f = fields();
    w.write_frame(time, step, kPoints, as_doubles(position.data()), f);
  }
};

void expect_frame(const std::string& h5, int f, double time, long step) {
  const FrameData d(f);
  const std::string frame = f == 0 ? "/frame_000000" : "/frame_000001";
  EXPECT_EQ(read_attribute(h5, frame, "time"), time);
  EXPECT_EQ(read_attribute(h5, frame, "step"), static_cast<double>(step));
  const std::string g = frame + "/particles";
  EXPECT_EQ(read_string_attribute(h5, g, "topology"), "Polyvertex");

  std::vector<std::size_t> dims;
  const auto pos = read_dataset(h5, g + "/position", &dims);
  EXPECT_EQ(dims, (std::vector<std::size_t>{kPoints, 3}));
  ASSERT_EQ(pos.size(), kPoints * 3);
  for (std::size_t i = 0; i < kPoints; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(pos[i * 3 + k], d.position[i][k]) << i << " " << k;

  const auto p = read_dataset(h5, g + "/node/pressure", &dims);
  EXPECT_EQ(dims, (std::vector<std::size_t>{kPoints}));
  EXPECT_EQ(p, d.pressure);

  const auto v = read_dataset(h5, g + "/node/velocity", &dims);
  EXPECT_EQ(dims, (std::vector<std::size_t>{kPoints, 3}));
  ASSERT_EQ(v.size(), kPoints * 3);
  for (std::size_t i = 0; i < kPoints; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(v[i * 3 + k], d.velocity[i][k]) << i << " " << k;

  const auto s = read_dataset(h5, g + "/node/stress", &dims);
  EXPECT_EQ(dims, (std::vector<std::size_t>{kPoints, 6}));
  ASSERT_EQ(s.size(), kPoints * 6);
  EXPECT_EQ(read_string_attribute(h5, g + "/node/stress", "component_order"), "xx,xy,xz,yy,yz,zz");
  for (std::size_t i = 0; i < kPoints; ++i) {
    const SymTensor& t = d.stress[i];
    const double xdmf_order[6] = {t.xx, t.xy, t.xz, t.yy, t.yz, t.zz};
    for (int k = 0; k < 6; ++k) EXPECT_EQ(s[i * 6 + k], xdmf_order[k]) << i << " " << k;
  }
}

TEST(FieldWriter, TwoFramesReadBackExactly) {
  const TempDir dir;
  const std::string out = (dir / "nested/out").string();  // parents are created too
  {
    FieldWriter w(out);
    EXPECT_EQ(w.frames(), 0u);
    EXPECT_EQ(w.h5_path(), out + "/fields.h5");
    FrameData(0).write(w, 0.0, 0);
    EXPECT_EQ(w.frames(), 1u);
    // Flushed: readable while the writer still holds the file (a run that dies later).
    expect_frame(w.h5_path(), 0, 0.0, 0);
    FrameData(1).write(w, 0.1, 1234567890123L);
    EXPECT_EQ(w.frames(), 2u);
  }
  const std::string h5 = out + "/fields.h5";
  expect_frame(h5, 0, 0.0, 0);
  expect_frame(h5, 1, 0.1, 1234567890123L);
}

TEST(FieldWriter, XdmfIndexIsValidAfterEveryFrame) {
  const TempDir dir;
  FieldWriter w(dir.str(), "bar");
  const fs::path xmf = dir / "bar.xmf";
  ASSERT_TRUE(fs::exists(xmf));  // valid (empty) index before the first frame
  EXPECT_EQ(count(slurp(xmf), "GridType=\"Uniform\""), 0u);

  FrameData(0).write(w, 0.0, 0);
  std::string text = slurp(xmf);
  EXPECT_EQ(count(text, "GridType=\"Uniform\""), 1u);
  EXPECT_EQ(xml_problem(text), "");
  EXPECT_NE(text.find("bar.h5:/frame_000000/particles/position"), std::string::npos) << text;
  EXPECT_NE(text.find("<Time Value=\"0\"/>"), std::string::npos) << text;
  EXPECT_EQ(text.find("frame_000001"), std::string::npos);

  FrameData(1).write(w, 0.1, 10);
  text = slurp(xmf);
  EXPECT_EQ(count(text, "<Grid Name=\"frame_"), 2u) << text;
  EXPECT_EQ(count(text, "<Grid Name=\"particles\" GridType=\"Uniform\""), 2u);
  EXPECT_EQ(count(text, "CollectionType=\"Spatial\""), 2u);
  EXPECT_EQ(count(text, "CollectionType=\"Temporal\""), 1u);
  EXPECT_NE(text.find("<Time Value=\"0.1\"/>"), std::string::npos) << text;
  EXPECT_EQ(count(text, "TopologyType=\"Polyvertex\" NumberOfElements=\"5\""), 2u);
  EXPECT_EQ(count(text, "GeometryType=\"XYZ\""), 2u);
  for (const char* frame : {"frame_000000", "frame_000001"}) {
    const std::string f = frame;
    EXPECT_NE(text.find("Dimensions=\"5 3\" NumberType=\"Float\" Precision=\"8\" "
                        "Format=\"HDF\">bar.h5:/" +
                        f + "/particles/position<"),
              std::string::npos)
        << f;
    EXPECT_NE(text.find(">bar.h5:/" + f + "/particles/node/pressure<"), std::string::npos) << f;
    EXPECT_NE(text.find(">bar.h5:/" + f + "/particles/node/velocity<"), std::string::npos) << f;
    EXPECT_NE(text.find("Dimensions=\"5 6\" NumberType=\"Float\" Precision=\"8\" "
                        "Format=\"HDF\">bar.h5:/" +
                        f + "/particles/node/stress<"),
              std::string::npos)
        << f;
  }
  EXPECT_EQ(count(text, "Name=\"pressure\" AttributeType=\"Scalar\" Center=\"Node\""), 2u);
  EXPECT_EQ(count(text, "Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\""), 2u);
  EXPECT_EQ(count(text, "Name=\"stress\" AttributeType=\"Tensor6\" Center=\"Node\""), 2u);
  EXPECT_EQ(xml_problem(text), "");
  EXPECT_FALSE(fs::exists(dir / "bar.xmf.tmp"));  // the temp file was renamed away
}

TEST(FieldWriter, SameCallsGiveSameBytes) {
  const TempDir dir;
  for (const char* sub : {"a", "b"}) {
    FieldWriter w((dir / sub).string());
    FrameData(0).write(w, 0.0, 0);
    FrameData(1).write(w, 0.25, 7);
  }
  const std::string a = slurp(dir / "a/fields.h5"), b = slurp(dir / "b/fields.h5");
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == b) << "HDF5 output differs between identical runs";
  EXPECT_EQ(slurp(dir / "a/fields.xmf"), slurp(dir / "b/fields.xmf"));
}

TEST(FieldWriter, EmptyFrameAndOtherComponentCounts) {
  const TempDir dir;
  FieldWriter w(dir.str());
  w.write_frame(0.0, 0, 0, nullptr, {});
  std::vector<std::size_t> dims;
  EXPECT_TRUE(read_dataset(w.h5_path(), "/frame_000000/particles/position", &dims).empty());
  EXPECT_EQ(dims, (std::vector<std::size_t>{0, 3}));

  const std::vector<double> pos = {0, 0, 0, 1, 1, 1};
  const std::vector<double> pair = {1.5, -2.5, 3.5, -4.5};
  const FieldView fields[] = {{"pair", pair.data(), 2}};
  w.write_frame(1.0, 1, 2, pos.data(), fields);
  EXPECT_EQ(read_dataset(w.h5_path(), "/frame_000001/particles/node/pair", &dims), pair);
  EXPECT_EQ(dims, (std::vector<std::size_t>{2, 2}));
  EXPECT_NE(slurp(w.xmf_path()).find("Name=\"pair\" AttributeType=\"Matrix\""), std::string::npos);
}

TEST(FieldWriter, BadFieldsAreRejectedWithoutAHalfFrame) {
  const TempDir dir;
  FieldWriter w(dir.str());
  const FrameData d(0);
  const double* pos = as_doubles(d.position.data());
  const std::vector<FieldView> twice = {scalar_field("p", d.pressure.data()),
                                        scalar_field("p", d.pressure.data())};
  EXPECT_THROW(w.write_frame(0.0, 0, kPoints, pos, twice), std::invalid_argument);
  const std::vector<FieldView> dot = {scalar_field(".", d.pressure.data())};
  EXPECT_THROW(w.write_frame(0.0, 0, kPoints, pos, dot), std::invalid_argument);
  const std::vector<FieldView> empty = {scalar_field("", d.pressure.data())};
  EXPECT_THROW(w.write_frame(0.0, 0, kPoints, pos, empty), std::invalid_argument);
  const std::vector<FieldView> short_field = {
      scalar_field("p", std::span(d.pressure).first(kPoints - 1))};
  EXPECT_THROW(w.write_frame(0.0, 0, kPoints, pos, short_field), std::invalid_argument);
  const std::vector<FieldView> slash = {scalar_field("a/b", d.pressure.data())};
  EXPECT_THROW(w.write_frame(0.0, 0, kPoints, pos, slash), std::invalid_argument);
  const std::vector<FieldView> none = {{"zero", d.pressure.data(), 0}};
  EXPECT_THROW(w.write_frame(0.0, 0, kPoints, pos, none), std::invalid_argument);
  EXPECT_THROW(w.write_frame(0.0, 0, kPoints, nullptr, {}), std::invalid_argument);
  EXPECT_EQ(w.frames(), 0u);
  d.write(w, 0.5, 3);  // still frame 0
  EXPECT_EQ(w.frames(), 1u);
  EXPECT_EQ(read_attribute(w.h5_path(), "/frame_000000", "time"), 0.5);
}

// Two unit hexahedra side by side along x, sharing the 4 nodes of the face x = 1 (12 nodes),
// plus a truss of two lines through 3 nodes, in frame f's current coordinates.
constexpr std::size_t kHexNodes = 12;
constexpr std::size_t kTrussNodes = 3;

std::int32_t hex_node(int i, int j, int k) {
  return k * 6 + j * 3 + i;
}

struct MeshFrame {
  std::vector<Vec3> hex_position, hex_velocity, truss_position;
  std::vector<double> hex_temperature, eroded, axial_force;
  std::vector<SymTensor> hex_stress;
  std::vector<std::int32_t> hexahedra, lines = {0, 1, 1, 2};
  std::vector<FieldView> hex_node_fields, hex_cell_fields, truss_cell_fields;
  FrameData particles;

  explicit MeshFrame(int f) : particles(f) {
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 3; ++i) {
          const double b = hex_node(i, j, k) + 0.1 * f;
          hex_position.push_back({i + b * 1e-3, j - b * 2e-3, k + b / 3.0});
          hex_velocity.push_back({b / 7.0, -b, b * b + 0.5});
          hex_temperature.push_back(293.0 + std::sqrt(b + 1.0));
        }
    for (int c = 0; c < 2; ++c) {
      hexahedra.insert(
          hexahedra.end(),
          {hex_node(c, 0, 0), hex_node(c + 1, 0, 0), hex_node(c + 1, 1, 0), hex_node(c, 1, 0),
           hex_node(c, 0, 1), hex_node(c + 1, 0, 1), hex_node(c + 1, 1, 1), hex_node(c, 1, 1)});
      const double b = c + 0.1 * f;
      hex_stress.push_back({-1.1e8 - b, -2.2e8 - b, -3.3e8 - b, 2.3e7 + b, 1.3e7 + b, 1.2e7 + b});
      eroded.push_back(c == 1 && f > 0 ? 1.0 : 0.0);
      axial_force.push_back(4.5e3 * (c + 1) - f);
    }
    for (std::size_t n = 0; n < kTrussNodes; ++n)
      truss_position.push_back({2.0 + static_cast<double>(n), 0.5 + 0.01 * f, -0.25});
    hex_node_fields = {vector_field("velocity", hex_velocity),
                       scalar_field("temperature", hex_temperature)};
    hex_cell_fields = {tensor_field("stress", hex_stress), scalar_field("eroded", eroded)};
    truss_cell_fields = {scalar_field("axial_force", axial_force)};
  }
  std::vector<FieldView> particle_fields() const { return particles.fields(); }
  std::vector<MeshBlock> meshes() const {
    return {{"hexahedra", CellKind::hexahedron, kHexNodes, as_doubles(hex_position.data()),
             hexahedra.size() / 8, hexahedra.data(), hex_node_fields, hex_cell_fields},
            {"trusses", CellKind::line, kTrussNodes, as_doubles(truss_position.data()),
             lines.size() / 2, lines.data(), std::span<const FieldView>(), truss_cell_fields}};
  }
  void write(FieldWriter& w, double time, long step) const {
    const auto pf = particle_fields();
    const PointBlock points[] = {{"particles", kPoints, as_doubles(particles.position.data()), pf}};
    w.write_frame(time, step, points, meshes());
  }
};

std::vector<double> flatten(const std::vector<Vec3>& v) {
  std::vector<double> out;
  for (const Vec3& p : v) out.insert(out.end(), {p[0], p[1], p[2]});
  return out;
}

TEST(FieldWriter, ParticlesHexahedraAndTrussesShareOneFrame) {
  const TempDir dir;
  FieldWriter w(dir.str(), "impact");
  const MeshFrame m(0);
  m.write(w, 2.5e-6, 40);
  EXPECT_EQ(w.frames(), 1u);
  const std::string h5 = w.h5_path();
  expect_frame(h5, 0, 2.5e-6, 40);  // the particle block, as from the single-cloud call

  const std::string hex = "/frame_000000/hexahedra";
  EXPECT_EQ(read_string_attribute(h5, hex, "topology"), "Hexahedron");
  std::vector<std::size_t> dims;
  EXPECT_EQ(read_dataset(h5, hex + "/position", &dims), flatten(m.hex_position));
  EXPECT_EQ(dims, (std::vector<std::size_t>{kHexNodes, 3}));
  const auto conn = read_dataset(h5, hex + "/connectivity", &dims);
  EXPECT_EQ(dims, (std::vector<std::size_t>{2, 8}));
  EXPECT_EQ(conn, std::vector<double>(m.hexahedra.begin(), m.hexahedra.end()));
  // The shared face: nodes 1, 4, 7, 10 appear in both cells.
  EXPECT_EQ(std::vector<double>(conn.begin() + 1, conn.begin() + 3), (std::vector<double>{1, 4}));
  EXPECT_EQ(std::vector<double>(conn.begin() + 8, conn.begin() + 8 + 4),
            (std::vector<double>{1, 2, 5, 4}));
  EXPECT_EQ(read_dataset(h5, hex + "/node/velocity", &dims), flatten(m.hex_velocity));
  EXPECT_EQ(dims, (std::vector<std::size_t>{kHexNodes, 3}));
  EXPECT_EQ(read_dataset(h5, hex + "/node/temperature", &dims), m.hex_temperature);
  EXPECT_EQ(dims, (std::vector<std::size_t>{kHexNodes}));
  EXPECT_EQ(read_dataset(h5, hex + "/cell/eroded", &dims), m.eroded);
  EXPECT_EQ(dims, (std::vector<std::size_t>{2}));
  const auto s = read_dataset(h5, hex + "/cell/stress", &dims);
  EXPECT_EQ(dims, (std::vector<std::size_t>{2, 6}));
  EXPECT_EQ(read_string_attribute(h5, hex + "/cell/stress", "component_order"),
            "xx,xy,xz,yy,yz,zz");
  for (std::size_t c = 0; c < 2; ++c) {
    const SymTensor& t = m.hex_stress[c];
    const double xdmf_order[6] = {t.xx, t.xy, t.xz, t.yy, t.yz, t.zz};
    for (int k = 0; k < 6; ++k) EXPECT_EQ(s[c * 6 + k], xdmf_order[k]) << c << " " << k;
  }

  const std::string truss = "/frame_000000/trusses";
  EXPECT_EQ(read_string_attribute(h5, truss, "topology"), "Polyline");
  EXPECT_EQ(read_dataset(h5, truss + "/position", &dims), flatten(m.truss_position));
  EXPECT_EQ(read_dataset(h5, truss + "/connectivity", &dims), (std::vector<double>{0, 1, 1, 2}));
  EXPECT_EQ(dims, (std::vector<std::size_t>{2, 2}));
  EXPECT_EQ(read_dataset(h5, truss + "/cell/axial_force", &dims), m.axial_force);
}

TEST(FieldWriter, UnchangedConnectivityIsStoredOnceAndLinked) {
  const TempDir dir;
  FieldWriter w(dir.str(), "mesh");
  MeshFrame(0).write(w, 0.0, 0);
  MeshFrame(1).write(w, 1e-6, 10);  // new buffers, same connectivity (an eroded cell is a field)
  MeshFrame changed(2);
  changed.hexahedra.resize(8);  // the second hexahedron removed: rewritten
  changed.hex_cell_fields = {};
  changed.write(w, 2e-6, 20);
  const std::string h5 = w.h5_path();

  EXPECT_EQ(read_link_target(h5, "/frame_000000/hexahedra/connectivity"), "");
  EXPECT_EQ(read_link_target(h5, "/frame_000001/hexahedra/connectivity"),
            "/frame_000000/hexahedra/connectivity");
  EXPECT_EQ(read_link_target(h5, "/frame_000002/hexahedra/connectivity"), "");
  for (const char* f : {"/frame_000001", "/frame_000002"})
    EXPECT_EQ(read_link_target(h5, std::string(f) + "/trusses/connectivity"),
              "/frame_000000/trusses/connectivity")
        << f;
  // Positions are stored in every frame (the mesh moves).
  EXPECT_EQ(read_link_target(h5, "/frame_000001/hexahedra/position"), "");

  // The link reads as the data it points at; the rewritten one has the new shape.
  std::vector<std::size_t> dims;
  const MeshFrame m0(0);
  EXPECT_EQ(read_dataset(h5, "/frame_000001/hexahedra/connectivity", &dims),
            std::vector<double>(m0.hexahedra.begin(), m0.hexahedra.end()));
  EXPECT_EQ(dims, (std::vector<std::size_t>{2, 8}));
  EXPECT_EQ(read_dataset(h5, "/frame_000002/hexahedra/connectivity", &dims),
            std::vector<double>(m0.hexahedra.begin(), m0.hexahedra.begin() + 8));
  EXPECT_EQ(dims, (std::vector<std::size_t>{1, 8}));
  EXPECT_EQ(read_dataset(h5, "/frame_000001/hexahedra/cell/eroded"), (std::vector<double>{0, 1}));

  // The index points every frame at the frame that stores the connectivity.
  const std::string text = slurp(w.xmf_path());
  EXPECT_EQ(xml_problem(text), "");
  EXPECT_EQ(count(text, ">mesh.h5:/frame_000000/hexahedra/connectivity<"), 2u) << text;
  EXPECT_EQ(count(text, "frame_000001/hexahedra/connectivity"), 0u);
  EXPECT_EQ(count(text, ">mesh.h5:/frame_000002/hexahedra/connectivity<"), 1u);
  EXPECT_EQ(count(text, ">mesh.h5:/frame_000000/trusses/connectivity<"), 3u);
  EXPECT_EQ(count(text, "trusses/connectivity"), 3u);
  EXPECT_EQ(count(text, "TopologyType=\"Hexahedron\" NumberOfElements=\"2\""), 2u);
  EXPECT_EQ(count(text, "TopologyType=\"Hexahedron\" NumberOfElements=\"1\""), 1u);
  // Positions and fields always point at their own frame.
  EXPECT_EQ(count(text, ">mesh.h5:/frame_000002/hexahedra/position<"), 1u);
  EXPECT_EQ(count(text, ">mesh.h5:/frame_000001/hexahedra/cell/eroded<"), 1u);
}

TEST(FieldWriter, XdmfIndexNestsOneSpatialCollectionPerFrame) {
  const TempDir dir;
  FieldWriter w(dir.str(), "m");
  for (int f = 0; f < 2; ++f) {
    MeshFrame(f).write(w, 1e-6 * f, f);
    EXPECT_EQ(xml_problem(slurp(w.xmf_path())), "") << "after frame " << f;
  }
  const std::string text = slurp(w.xmf_path());
  EXPECT_EQ(count(text, "CollectionType=\"Temporal\""), 1u);
  EXPECT_EQ(count(text,
                  "<Grid Name=\"frame_000001\" GridType=\"Collection\" "
                  "CollectionType=\"Spatial\">\n        <Time Value=\"1e-06\"/>"),
            1u)
      << text;
  EXPECT_EQ(count(text, "GridType=\"Uniform\""), 6u);
  EXPECT_EQ(count(text, "<Time "), 2u);  // on the spatial collections only
  EXPECT_EQ(count(text,
                  "<Grid Name=\"hexahedra\" GridType=\"Uniform\">\n          "
                  "<Topology TopologyType=\"Hexahedron\" NumberOfElements=\"2\">\n"
                  "            <DataItem Dimensions=\"2 8\" NumberType=\"Int\" "
                  "Precision=\"4\" Format=\"HDF\">m.h5:/frame_000000/hexahedra/"
                  "connectivity</DataItem>"),
            2u)
      << text;
  EXPECT_EQ(count(text,
                  "<Topology TopologyType=\"Polyline\" NumberOfElements=\"2\" "
                  "NodesPerElement=\"2\">\n            <DataItem Dimensions=\"2 2\" "
                  "NumberType=\"Int\" Precision=\"4\""),
            2u);
  EXPECT_EQ(count(text,
                  "TopologyType=\"Polyvertex\" NumberOfElements=\"5\" "
                  "NodesPerElement=\"1\"/>"),
            2u);
  EXPECT_EQ(count(text,
                  "<DataItem Dimensions=\"12 3\" NumberType=\"Float\" Precision=\"8\" "
                  "Format=\"HDF\">m.h5:/frame_000001/hexahedra/position<"),
            1u);
  EXPECT_EQ(count(text,
                  "<Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">"
                  "\n            <DataItem Dimensions=\"12 3\""),
            2u);
  EXPECT_EQ(count(text,
                  "<Attribute Name=\"temperature\" AttributeType=\"Scalar\" "
                  "Center=\"Node\">\n            <DataItem Dimensions=\"12\""),
            2u);
  EXPECT_EQ(count(text,
                  "<Attribute Name=\"stress\" AttributeType=\"Tensor6\" Center=\"Cell\">"
                  "\n            <DataItem Dimensions=\"2 6\""),
            2u);
  EXPECT_EQ(count(text, "<Attribute Name=\"eroded\" AttributeType=\"Scalar\" Center=\"Cell\">"),
            2u);
  EXPECT_EQ(count(text,
                  "<Attribute Name=\"axial_force\" AttributeType=\"Scalar\" "
                  "Center=\"Cell\">\n            <DataItem Dimensions=\"2\""),
            2u);
  EXPECT_EQ(count(text, "Center=\"Node\""), 2u * (3 + 2));  // particles 3, hexahedra 2
  EXPECT_EQ(count(text, "Center=\"Cell\""), 2u * (2 + 1));  // hexahedra 2, trusses 1
  // The checker itself catches a torn index (a write cut short).
  EXPECT_NE(xml_problem(text.substr(0, text.size() / 2)), "");
}

TEST(FieldWriter, SingleCloudCallIsAOneBlockFrame) {
  const TempDir dir;
  const FrameData d(0);
  {
    FieldWriter w((dir / "old").string());
    d.write(w, 0.5, 5);
  }
  {
    FieldWriter w((dir / "new").string());
    const auto fields = d.fields();
    const PointBlock points[] = {{"particles", kPoints, as_doubles(d.position.data()), fields}};
    w.write_frame(0.5, 5, points, {});
  }
  EXPECT_TRUE(slurp(dir / "old/fields.h5") == slurp(dir / "new/fields.h5"));
  EXPECT_EQ(slurp(dir / "old/fields.xmf"), slurp(dir / "new/fields.xmf"));
}

TEST(FieldWriter, SameMultiBlockCallsGiveSameBytes) {
  const TempDir dir;
  for (const char* sub : {"a", "b"}) {
    FieldWriter w((dir / sub).string(), "m");
    MeshFrame(0).write(w, 0.0, 0);
    MeshFrame(1).write(w, 0.25, 7);
  }
  const std::string a = slurp(dir / "a/m.h5"), b = slurp(dir / "b/m.h5");
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == b) << "HDF5 output differs between identical runs";
  EXPECT_EQ(slurp(dir / "a/m.xmf"), slurp(dir / "b/m.xmf"));
}

TEST(FieldWriter, BadMeshInputIsRejectedWithoutAHalfFrame) {
  const TempDir dir;
  FieldWriter w(dir.str(), "bad");
  const MeshFrame m(0);
  const auto pf = m.particle_fields();
  const PointBlock points[] = {{"particles", kPoints, as_doubles(m.particles.position.data()), pf}};
  // Each call breaks one thing in an otherwise good frame.
  auto attempt = [&](auto&& spoil) {
    std::vector<MeshBlock> meshes = m.meshes();
    std::vector<PointBlock> pts(std::begin(points), std::end(points));
    std::vector<FieldView> cell_fields = m.hex_cell_fields;
    spoil(pts, meshes, cell_fields);
    meshes[0].cell_fields = cell_fields;
    try {
      w.write_frame(0.0, 0, pts, meshes);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  using Pts = std::vector<PointBlock>;
  using Meshes = std::vector<MeshBlock>;
  using Fields = std::vector<FieldView>;
  const std::vector<double> three(3, 1.0);
  const std::string short_cell = attempt([&](Pts&, Meshes&, Fields& f) {
    f.push_back(scalar_field("damage", three));  // 3 values for 2 cells
  });
  EXPECT_NE(short_cell.find(w.h5_path()), std::string::npos) << short_cell;
  EXPECT_NE(short_cell.find("block 'hexahedra': cell field 'damage' has 3 values, expected 2"),
            std::string::npos)
      << short_cell;
  EXPECT_NE(attempt([&](Pts&, Meshes&, Fields& f) { f[1].name = "a/b"; }), "accepted");
  EXPECT_NE(attempt([&](Pts&, Meshes&, Fields& f) { f[1].name = "stress"; }), "accepted");
  EXPECT_NE(attempt([&](Pts&, Meshes&, Fields& f) { f[0].components = 0; }), "accepted");
  EXPECT_NE(attempt([&](Pts&, Meshes& ms, Fields&) { ms[0].n_nodes = 11; }), "accepted");
  const std::vector<std::int32_t> out_of_range = {0, 3};
  const std::string bad_node = attempt([&](Pts&, Meshes& ms, Fields&) {
    ms[1].connectivity = out_of_range.data();
    ms[1].n_cells = 1;
    ms[1].cell_fields = {};
  });
  EXPECT_NE(bad_node.find("block 'trusses': cell 0 refers to node 3 of 3"), std::string::npos)
      << bad_node;
  const std::vector<std::int32_t> negative = {-1, 0};
  EXPECT_NE(attempt([&](Pts&, Meshes& ms, Fields&) {
              ms[1].connectivity = negative.data();
              ms[1].n_cells = 1;
              ms[1].cell_fields = {};
            }),
            "accepted");
  EXPECT_NE(attempt([&](Pts&, Meshes& ms, Fields&) { ms[0].connectivity = nullptr; }), "accepted");
  EXPECT_NE(attempt([&](Pts&, Meshes& ms, Fields&) { ms[0].node_positions = nullptr; }),
            "accepted");
  EXPECT_NE(attempt([&](Pts&, Meshes& ms, Fields&) { ms[1].name = "particles"; }), "accepted");
  EXPECT_NE(attempt([&](Pts&, Meshes& ms, Fields&) { ms[1].name = "."; }), "accepted");
  EXPECT_NE(attempt([&](Pts& ps, Meshes&, Fields&) { ps[0].name = ""; }), "accepted");

  EXPECT_EQ(w.frames(), 0u);
  EXPECT_THROW(read_attribute(w.h5_path(), "/frame_000000", "time"), std::runtime_error);
  EXPECT_EQ(slurp(w.xmf_path()).find("frame_000000"), std::string::npos);
  // A rejected frame registered no connectivity: the first good one stores its own.
  m.write(w, 0.5, 3);
  EXPECT_EQ(w.frames(), 1u);
  EXPECT_EQ(read_attribute(w.h5_path(), "/frame_000000", "time"), 0.5);
  EXPECT_EQ(read_link_target(w.h5_path(), "/frame_000000/hexahedra/connectivity"), "");
  EXPECT_EQ(attempt([](Pts&, Meshes&, Fields&) {}), "accepted");  // the harness itself is sound
}

TEST(FieldWriter, UnwritableDirectoryThrowsNamingThePath) {
  try {
    FieldWriter w("/proc/afemp_no");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/proc/afemp_no"), std::string::npos) << e.what();
  }
}

TEST(FieldWriter, ReaderNamesWhatIsMissing) {
  const TempDir dir;
  {
    FieldWriter w(dir.str());
    FrameData(0).write(w, 0.0, 0);
  }
  const std::string h5 = (dir / "fields.h5").string();
  try {
    read_dataset(h5, "/frame_000000/nothing");
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/frame_000000/nothing"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_attribute(h5, "/frame_000000", "nothing"), std::runtime_error);
  EXPECT_THROW(read_dataset((dir / "absent.h5").string(), "/x"), std::runtime_error);
}

}  // namespace
}  // namespace afemp::core
