#include <gtest/gtest.h>

#include "colag/common/map_patch_codec.hpp"
#include "colag/common/random.hpp"

using namespace colag;

namespace {

PatchCells random_patch(Rng& rng, int w, int h, double mean_run) {
  PatchCells p;
  p.width = w;
  p.height = h;
  auto state = CellState::kFree;
  for (int i = 0; i < w * h; ++i) {
    if (rng.uniform() < 1.0 / mean_run) state = static_cast<CellState>(rng.below(3));
    p.cells[static_cast<std::size_t>(i)] = state;
  }
  return p;
}

bool same(const PatchCells& a, const PatchCells& b) {
  if (a.width != b.width || a.height != b.height) return false;
  for (int i = 0; i < a.width * a.height; ++i) {
    if (a.cells[static_cast<std::size_t>(i)] != b.cells[static_cast<std::size_t>(i)]) return false;
  }
  return true;
}

msg::MapPatch encoded(const PatchCells& p) {
  msg::MapPatch m;
  EXPECT_TRUE(encode_patch(p, m));
  return m;
}

}  // namespace

TEST(MapPatchCodec, RoundTripsRandomPatchesAndPicksTheSmallerEncoding) {
  Rng rng(5);
  int rle = 0, packed = 0, rows = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int w = 1 + static_cast<int>(rng.below(64)), h = 1 + static_cast<int>(rng.below(64));
    const double mean_run = trial % 2 ? 1.5 : 80.0;  // noisy or map-like
    const PatchCells p = random_patch(rng, w, h, mean_run);
    const msg::MapPatch m = encoded(p);
    EXPECT_LE(m.data.count, (w * h + 3) / 4);
    (m.encoding == msg::MapPatchEncoding::kRunLength  ? rle
     : m.encoding == msg::MapPatchEncoding::kRowDelta ? rows
                                                      : packed)++;
    PatchCells out;
    ASSERT_TRUE(decode_patch(m, out)) << "trial " << trial;
    ASSERT_TRUE(same(p, out)) << "trial " << trial;
  }
  EXPECT_GT(rle + rows, 500);
  EXPECT_GT(packed, 500);
}

TEST(MapPatchCodec, RowDeltaCodesABoxByItsEdges) {
  PatchCells p;
  p.width = p.height = 50;
  for (int y = 10; y < 19; ++y) {
    for (int x = 20; x < 29; ++x)
      p.cells[static_cast<std::size_t>(y) * 50 + x] = CellState::kOccupied;
  }
  const msg::MapPatch m = encoded(p);
  EXPECT_EQ(m.encoding, msg::MapPatchEncoding::kRowDelta);
  EXPECT_LE(m.data.count, 12);  // free, box top edge, free, box bottom edge, free
  PatchCells out;
  ASSERT_TRUE(decode_patch(m, out));
  EXPECT_TRUE(same(p, out));
  // A row-delta stream that XORs a cell into the invalid value 3 is rejected.
  msg::MapPatch bad = m;
  bad.data[0] = static_cast<std::uint8_t>((bad.data[0] & 0xFC) | 3);
  EXPECT_FALSE(decode_patch(bad, out));
}

TEST(MapPatchCodec, AFreePatchIsTiny) {
  PatchCells p;
  p.width = 50;
  p.height = 50;  // all free
  const msg::MapPatch m = encoded(p);
  EXPECT_NE(m.encoding, msg::MapPatchEncoding::kPacked2Bit);
  EXPECT_EQ(m.data.count, 2);  // one run of 2500 cells
}

TEST(MapPatchCodec, RejectsEveryMalformedPatchAndLeavesTheOutputAlone) {
  Rng rng(9);
  const PatchCells p = random_patch(rng, 20, 10, 1.5);  // packed
  const msg::MapPatch good = encoded(p);
  ASSERT_EQ(good.encoding, msg::MapPatchEncoding::kPacked2Bit);
  PatchCells q = random_patch(rng, 30, 30, 60.0);  // run-length
  const msg::MapPatch good_rle = encoded(q);
  ASSERT_EQ(good_rle.encoding, msg::MapPatchEncoding::kRunLength);

  PatchCells out;
  out.width = 7;  // sentinel: must survive every failed decode
  const auto rejects = [&](msg::MapPatch m, const char* why) {
    EXPECT_FALSE(decode_patch(m, out)) << why;
    EXPECT_EQ(out.width, 7) << why;
  };
  msg::MapPatch m = good;
  m.width_cells = 0;
  rejects(m, "zero width");
  m = good;
  m.height_cells = limits::kMaxPatchSideCells + 1;
  rejects(m, "too tall");
  m = good;
  m.data.count = static_cast<std::uint16_t>(good.data.count - 1);
  rejects(m, "packed payload short");
  m = good;
  m.data.count = static_cast<std::uint16_t>(good.data.count + 1);
  rejects(m, "packed payload long");
  m = good;
  m.data[3] = 0xFF;  // cell value 3
  rejects(m, "invalid cell value");
  m = good;
  m.width_cells = 19;  // 190 cells: the last byte's padding now holds a cell
  m.data.count = 48;
  m.data[47] = 0xC0;
  rejects(m, "non-zero padding");
  m = good;
  m.encoding = static_cast<msg::MapPatchEncoding>(3);
  rejects(m, "unknown encoding");
  m = good;
  m.data.count = limits::kMaxPatchBytes + 1;
  rejects(m, "payload over the bound");

  m = good_rle;
  m.data.count = static_cast<std::uint16_t>(good_rle.data.count - 1);
  rejects(m, "run-length: cells missing");
  m = good_rle;
  m.data[m.data.count] = 0x00;  // one extra run of one free cell
  m.data.count = static_cast<std::uint16_t>(m.data.count + 1);
  rejects(m, "run-length: cells beyond the patch");
  m = good_rle;
  m.data[m.data.count - 1] |= 0x80;  // the last varint claims a continuation that never comes
  rejects(m, "run-length: truncated varint");
  m = good_rle;
  m.data.count = 4;
  m.data[0] = m.data[1] = m.data[2] = m.data[3] = 0xFF;
  rejects(m, "run-length: overlong varint");
  m = good_rle;
  m.data[0] = static_cast<std::uint8_t>((m.data[0] & 0xFC) | 3);
  rejects(m, "run-length: invalid state");

  ASSERT_TRUE(decode_patch(good_rle, out));
  EXPECT_TRUE(same(q, out));
}

TEST(MapPatchCodec, EncoderRejectsBadInput) {
  PatchCells p;
  msg::MapPatch m;
  p.width = 0;
  p.height = 5;
  EXPECT_FALSE(encode_patch(p, m));
  p.width = 65;
  EXPECT_FALSE(encode_patch(p, m));
  p.width = 2;
  p.height = 2;
  p.cells[1] = static_cast<CellState>(3);
  EXPECT_FALSE(encode_patch(p, m));
}
