// The checkpoint archive (core/state_archive.hpp). Reference: identity. Every kind of item a
// model saves (doubles, tensors, integers, flags, records, texts, lists of lists, one value)
// reads back bit for bit, NaN and -0.0 included; the file is plain HDF5 (a Vec3 array is an
// n x 3 array of doubles); and an item missing or stored with another layout is refused with
// the file, the item's path and the reason.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/output/field_writer.hpp"
#include "core/state_archive.hpp"
#include "scratch_dir.hpp"

namespace afemp::core {
namespace {

struct Record {
  std::int32_t a = 0;
  double b = 0.0;
};

template <class T>
bool same_bytes(const std::vector<T>& x, const std::vector<T>& y) {
  return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(T)) == 0;
}

TEST(StateArchive, EveryKindOfItemReadsBackBitForBit) {
  test::ScratchDir dir;
  const std::string path = dir.file("state.h5");
  std::vector<double> d{1.0 / 3.0, -0.0, std::numeric_limits<double>::quiet_NaN(), 1e-310};
  std::vector<Vec3> v{{1, 2, 3}, {4.5, -6, 7e300}};
  std::vector<SymTensor> t(3);
  t[1].xy = 0.1;
  std::vector<Mat3> m(2);
  m[0].m[2][1] = -9.0;
  std::vector<std::array<Vec3, 4>> hg(2);
  hg[1][3].z = 42.0;
  std::vector<std::int32_t> i32{-1, 7};
  std::vector<std::uint8_t> flags{0, 1, 255};
  std::vector<std::int64_t> i64{std::numeric_limits<std::int64_t>::min()};
  std::vector<Record> records{{1, 2.5}, {-3, 1e-9}};
  std::vector<double> empty;
  std::vector<std::vector<std::size_t>> lists{{1, 2}, {}, {3}};
  std::vector<std::string> texts{"", "a b", "line\nbreak"};
  std::string text = "scene = \"x\"\n";
  long step = 123456789012;
  double time = 0.1 + 0.2;
  bool flag = true;
  Vec3 one{-1, 0, 1};
  const auto visit = [&](StateArchive& a) {
    const StateArchive::Group g(a, "model");
    a.item("d", d);
    a.item("v", v);
    a.item("t", t);
    a.item("m", m);
    a.item("hg", hg);
    a.item("i32", i32);
    a.item("flags", flags);
    a.item("i64", i64);
    a.item("records", records);
    a.item("empty", empty);
    a.item("lists", lists);
    a.item("texts", texts);
    a.item("text", text);
    a.item("step", step);
    a.item("time", time);
    a.item("flag", flag);
    a.item("one", one);
  };
  {
    StateArchive a(path, StateArchive::Mode::save);
    visit(a);
    a.close();
  }
  const auto d0 = d;
  const auto v0 = v;
  const auto t0 = t;
  const auto m0 = m;
  const auto hg0 = hg;
  const auto i320 = i32;
  const auto flags0 = flags;
  const auto i640 = i64;
  const auto records0 = records;
  const auto lists0 = lists;
  const auto texts0 = texts;
  const std::string text0 = text;
  d.clear(), v.clear(), t.clear(), m.clear(), hg.clear(), i32.clear(), flags.clear(), i64.clear();
  records.clear(), lists.clear(), texts.clear(), text.clear();
  empty.assign(5, 1.0);
  step = 0, time = 0.0, flag = false, one = Vec3{};
  {
    StateArchive a(path, StateArchive::Mode::load);
    visit(a);
  }
  EXPECT_TRUE(same_bytes(d, d0));
  EXPECT_TRUE(same_bytes(v, v0));
  EXPECT_TRUE(same_bytes(t, t0));
  EXPECT_TRUE(same_bytes(m, m0));
  EXPECT_TRUE(same_bytes(hg, hg0));
  EXPECT_EQ(i32, i320);
  EXPECT_EQ(flags, flags0);
  EXPECT_EQ(i64, i640);
  ASSERT_EQ(records.size(), 2u);
  EXPECT_EQ(records[1].a, -3);
  EXPECT_EQ(records[1].b, 1e-9);
  EXPECT_TRUE(empty.empty());
  EXPECT_EQ(lists, lists0);
  EXPECT_EQ(texts, texts0);
  EXPECT_EQ(text, text0);
  EXPECT_EQ(step, 123456789012);
  EXPECT_EQ(time, 0.1 + 0.2);
  EXPECT_TRUE(flag);
  EXPECT_EQ(one.z, 1.0);
  // Plain HDF5: the Vec3 array is 2 x 3 doubles.
  std::vector<std::size_t> dims;
  const std::vector<double> raw = read_dataset(path, "model/v", &dims);
  EXPECT_EQ(dims, (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(raw[5], 7e300);
}

// In memory (how a state goes from rank to rank): the image is the file a save would write,
// readable from the bytes and, written out, as a checkpoint file; no file appears on the way;
// bytes that are no HDF5 file are refused with the archive's name.
TEST(StateArchive, AnInMemoryImageReadsBackAsItsBytesAndAsAFile) {
  test::ScratchDir dir;
  std::vector<Vec3> v{{1, 2, 3}, {4.5, -6, 7e300}};
  double time = 0.1 + 0.2;
  std::vector<std::byte> image;
  {
    StateArchive a("the state", StateArchive::InMemory{});
    const StateArchive::Group g(a, "model");
    a.item("v", v);
    a.item("time", time);
    image = a.image();
  }
  EXPECT_GT(image.size(), 100u);
  EXPECT_FALSE(std::filesystem::exists("the state"));
  const std::string path = dir.file("image.h5");
  {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(image.data()),
              static_cast<std::streamsize>(image.size()));
  }
  for (int from_file = 0; from_file < 2; ++from_file) {
    std::vector<Vec3> v1;
    double time1 = 0.0;
    std::unique_ptr<StateArchive> a =
        from_file ? std::make_unique<StateArchive>(path, StateArchive::Mode::load)
                  : std::make_unique<StateArchive>("the state", image);
    const StateArchive::Group g(*a, "model");
    a->item("v", v1);
    a->item("time", time1);
    ASSERT_EQ(v1.size(), 2u) << from_file;
    EXPECT_EQ(v1[1].z, 7e300);
    EXPECT_EQ(time1, 0.1 + 0.2);
  }
  std::vector<std::byte> junk(image.size(), std::byte{7});
  try {
    StateArchive a("the state", junk);
    FAIL() << "junk read as an archive";
  } catch (const CheckpointError& e) {
    EXPECT_NE(std::string(e.what()).find("the state: cannot open its image"), std::string::npos)
        << e.what();
  }
}

TEST(StateArchive, AMissingOrMismatchedItemIsRefusedNamingFileAndItem) {
  test::ScratchDir dir;
  const std::string path = dir.file("state.h5");
  {
    StateArchive a(path, StateArchive::Mode::save);
    const StateArchive::Group g(a, "mpm");
    std::vector<double> x{1.0, 2.0};
    a.item("x", x);
    a.close();
  }
  StateArchive a(path, StateArchive::Mode::load);
  const StateArchive::Group g(a, "mpm");
  std::vector<double> y;
  try {
    a.item("y", y);
    ADD_FAILURE() << "a missing item was read";
  } catch (const CheckpointError& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": /mpm/y: missing (written by another afemp version, or another scene)");
  }
  std::vector<Vec3> x;
  try {
    a.item("x", x);
    ADD_FAILURE() << "doubles were read as Vec3";
  } catch (const CheckpointError& e) {
    EXPECT_NE(
        std::string(e.what()).find(
            path + ": /mpm/x: is stored with 1 components of 8 bytes, this build expects 3 of 8"),
        std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace afemp::core
