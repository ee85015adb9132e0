// FieldWriter: every dataset and attribute reads back bit for bit, tensors come back in the
// documented XDMF order, and the .xmf index is valid after every frame (crash safety).
// Files go to a per-test temporary directory that is removed afterwards.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "scratch_dir.hpp"
#include "core/output/field_writer.hpp"
#include "core/tensor.hpp"

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
  const std::string g = f == 0 ? "/frame_000000" : "/frame_000001";
  EXPECT_EQ(read_attribute(h5, g, "time"), time);
  EXPECT_EQ(read_attribute(h5, g, "step"), static_cast<double>(step));

  std::vector<std::size_t> dims;
  const auto pos = read_dataset(h5, g + "/position", &dims);
  EXPECT_EQ(dims, (std::vector<std::size_t>{kPoints, 3}));
  ASSERT_EQ(pos.size(), kPoints * 3);
  for (std::size_t i = 0; i < kPoints; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(pos[i * 3 + k], d.position[i][k]) << i << " " << k;

  const auto p = read_dataset(h5, g + "/pressure", &dims);
  EXPECT_EQ(dims, (std::vector<std::size_t>{kPoints}));
  EXPECT_EQ(p, d.pressure);

  const auto v = read_dataset(h5, g + "/velocity", &dims);
  EXPECT_EQ(dims, (std::vector<std::size_t>{kPoints, 3}));
  ASSERT_EQ(v.size(), kPoints * 3);
  for (std::size_t i = 0; i < kPoints; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(v[i * 3 + k], d.velocity[i][k]) << i << " " << k;

  const auto s = read_dataset(h5, g + "/stress", &dims);
  EXPECT_EQ(dims, (std::vector<std::size_t>{kPoints, 6}));
  ASSERT_EQ(s.size(), kPoints * 6);
  EXPECT_EQ(read_string_attribute(h5, g + "/stress", "component_order"), "xx,xy,xz,yy,yz,zz");
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
    EXPECT_EQ(w.h5_path(), out + "/particles.h5");
    FrameData(0).write(w, 0.0, 0);
    EXPECT_EQ(w.frames(), 1u);
    // Flushed: readable while the writer still holds the file (a run that dies later).
    expect_frame(w.h5_path(), 0, 0.0, 0);
    FrameData(1).write(w, 0.1, 1234567890123L);
    EXPECT_EQ(w.frames(), 2u);
  }
  const std::string h5 = out + "/particles.h5";
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
  EXPECT_NE(text.find("bar.h5:/frame_000000/position"), std::string::npos) << text;
  EXPECT_NE(text.find("<Time Value=\"0\"/>"), std::string::npos) << text;
  EXPECT_EQ(text.find("frame_000001"), std::string::npos);

  FrameData(1).write(w, 0.1, 10);
  text = slurp(xmf);
  EXPECT_EQ(count(text, "<Grid Name=\"frame_"), 2u) << text;
  EXPECT_EQ(count(text, "GridType=\"Uniform\""), 2u);
  EXPECT_EQ(count(text, "CollectionType=\"Temporal\""), 1u);
  EXPECT_NE(text.find("<Time Value=\"0.1\"/>"), std::string::npos) << text;
  EXPECT_EQ(count(text, "TopologyType=\"Polyvertex\" NumberOfElements=\"5\""), 2u);
  EXPECT_EQ(count(text, "GeometryType=\"XYZ\""), 2u);
  for (const char* frame : {"frame_000000", "frame_000001"}) {
    const std::string f = frame;
    EXPECT_NE(text.find("Dimensions=\"5 3\" NumberType=\"Float\" Precision=\"8\" "
                        "Format=\"HDF\">bar.h5:/" + f + "/position<"),
              std::string::npos) << f;
    EXPECT_NE(text.find(">bar.h5:/" + f + "/pressure<"), std::string::npos) << f;
    EXPECT_NE(text.find(">bar.h5:/" + f + "/velocity<"), std::string::npos) << f;
    EXPECT_NE(text.find("Dimensions=\"5 6\" NumberType=\"Float\" Precision=\"8\" "
                        "Format=\"HDF\">bar.h5:/" + f + "/stress<"),
              std::string::npos) << f;
  }
  EXPECT_EQ(count(text, "Name=\"pressure\" AttributeType=\"Scalar\" Center=\"Node\""), 2u);
  EXPECT_EQ(count(text, "Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\""), 2u);
  EXPECT_EQ(count(text, "Name=\"stress\" AttributeType=\"Tensor6\" Center=\"Node\""), 2u);
  EXPECT_NE(text.find("</Xdmf>"), std::string::npos);  // complete document
  // Balanced elements (a cheap well-formedness check).
  EXPECT_EQ(count(text, "<Grid "), count(text, "</Grid>"));
  EXPECT_EQ(count(text, "<Attribute "), count(text, "</Attribute>"));
  EXPECT_EQ(count(text, "<DataItem "), count(text, "</DataItem>"));
  EXPECT_FALSE(fs::exists(dir / "bar.xmf.tmp"));  // the temp file was renamed away
}

TEST(FieldWriter, SameCallsGiveSameBytes) {
  const TempDir dir;
  for (const char* sub : {"a", "b"}) {
    FieldWriter w((dir / sub).string());
    FrameData(0).write(w, 0.0, 0);
    FrameData(1).write(w, 0.25, 7);
  }
  const std::string a = slurp(dir / "a/particles.h5"), b = slurp(dir / "b/particles.h5");
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == b) << "HDF5 output differs between identical runs";
  EXPECT_EQ(slurp(dir / "a/particles.xmf"), slurp(dir / "b/particles.xmf"));
}

TEST(FieldWriter, EmptyFrameAndOtherComponentCounts) {
  const TempDir dir;
  FieldWriter w(dir.str());
  w.write_frame(0.0, 0, 0, nullptr, {});
  std::vector<std::size_t> dims;
  EXPECT_TRUE(read_dataset(w.h5_path(), "/frame_000000/position", &dims).empty());
  EXPECT_EQ(dims, (std::vector<std::size_t>{0, 3}));

  const std::vector<double> pos = {0, 0, 0, 1, 1, 1};
  const std::vector<double> pair = {1.5, -2.5, 3.5, -4.5};
  const FieldView fields[] = {{"pair", pair.data(), 2}};
  w.write_frame(1.0, 1, 2, pos.data(), fields);
  EXPECT_EQ(read_dataset(w.h5_path(), "/frame_000001/pair", &dims), pair);
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
  const std::vector<FieldView> reserved = {scalar_field("position", d.pressure.data())};
  EXPECT_THROW(w.write_frame(0.0, 0, kPoints, pos, reserved), std::invalid_argument);
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
  const std::string h5 = (dir / "particles.h5").string();
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
