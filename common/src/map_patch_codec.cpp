#include "colag/common/map_patch_codec.hpp"

#include <algorithm>

namespace colag {

namespace {

constexpr std::size_t packed_bytes(std::size_t cells) {
  return (cells + 3) / 4;
}

bool valid_size(int w, int h) {
  return w > 0 && h > 0 && w <= limits::kMaxPatchSideCells && h <= limits::kMaxPatchSideCells;
}

void encode_packed(const PatchCells& in, std::size_t n, std::uint8_t* data) {
  std::fill(data, data + packed_bytes(n), std::uint8_t{0});
  for (std::size_t i = 0; i < n; ++i) {
    data[i / 4] |= static_cast<std::uint8_t>(static_cast<unsigned>(in.cells[i]) << (2 * (i % 4)));
  }
}

// The symbol coded for cell i: its state, or (row delta) its state XOR the one below.
unsigned symbol(const PatchCells& in, std::size_t i, bool row_delta) {
  const auto w = static_cast<std::size_t>(in.width);
  const unsigned below = row_delta && i >= w ? static_cast<unsigned>(in.cells[i - w]) : 0U;
  return static_cast<unsigned>(in.cells[i]) ^ below;
}

// Returns the encoded size, or 0 if it would exceed `cap` bytes.
std::size_t encode_rle(const PatchCells& in, std::size_t n, bool row_delta, std::uint8_t* data,
                       std::size_t cap) {
  std::size_t len = 0;
  for (std::size_t i = 0; i < n;) {
    const unsigned sym = symbol(in, i, row_delta);
    std::size_t j = i + 1;
    while (j < n && symbol(in, j, row_delta) == sym)
      ++j;
    std::uint32_t v = sym | static_cast<std::uint32_t>((j - i - 1) << 2);
    do {
      if (len == cap) return 0;
      const auto byte = static_cast<std::uint8_t>(v & 0x7F);
      v >>= 7;
      data[len++] = static_cast<std::uint8_t>(byte | (v != 0 ? 0x80 : 0x00));
    } while (v != 0);
    i = j;
  }
  return len;
}

Status decode_packed(const msg::MapPatch& in, std::size_t n, PatchCells& out) {
  if (in.data.count != packed_bytes(n)) return {Errc::kInvalidArgument, "packed patch: wrong size"};
  for (std::size_t i = 0; i < packed_bytes(n) * 4; ++i) {
    const unsigned v = (in.data.items[i / 4] >> (2 * (i % 4))) & 3U;
    if (i >= n) {
      if (v != 0) return {Errc::kCorrupt, "packed patch: non-zero padding"};
      continue;
    }
    if (v > 2) return {Errc::kCorrupt, "packed patch: invalid cell value"};
    out.cells[i] = static_cast<CellState>(v);
  }
  return Status::ok();
}

Status decode_rle(const msg::MapPatch& in, std::size_t n, bool row_delta, PatchCells& out) {
  std::size_t pos = 0, cell = 0;
  while (pos < in.data.count) {
    std::uint32_t v = 0;
    int shift = 0;
    for (;;) {
      if (pos == in.data.count) return {Errc::kCorrupt, "run-length patch: truncated run"};
      if (shift > 14) return {Errc::kCorrupt, "run-length patch: run too long"};
      const std::uint8_t b = in.data.items[pos++];
      v |= static_cast<std::uint32_t>(b & 0x7F) << shift;
      shift += 7;
      if ((b & 0x80) == 0) break;
    }
    const unsigned sym = v & 3U;
    const std::size_t run = (v >> 2) + 1;
    if (run > n - cell) return {Errc::kCorrupt, "run-length patch: more cells than the patch"};
    const auto w = static_cast<std::size_t>(in.width_cells);
    for (std::size_t k = cell; k < cell + run; ++k) {
      const unsigned state =
          sym ^ (row_delta && k >= w ? static_cast<unsigned>(out.cells[k - w]) : 0U);
      if (state > 2) return {Errc::kCorrupt, "run-length patch: invalid cell value"};
      out.cells[k] = static_cast<CellState>(state);
    }
    cell += run;
  }
  if (cell != n) return {Errc::kCorrupt, "run-length patch: fewer cells than the patch"};
  return Status::ok();
}

}  // namespace

Status encode_patch(const PatchCells& in, msg::MapPatch& out) {
  if (!valid_size(in.width, in.height)) return {Errc::kInvalidArgument, "patch size out of range"};
  const auto n = static_cast<std::size_t>(in.width) * static_cast<std::size_t>(in.height);
  for (std::size_t i = 0; i < n; ++i) {
    if (static_cast<unsigned>(in.cells[i]) > 2)
      return {Errc::kInvalidArgument, "invalid cell state"};
  }
  out.width_cells = static_cast<std::uint16_t>(in.width);
  out.height_cells = static_cast<std::uint16_t>(in.height);
  // The smallest of the three; run-length forms only when strictly smaller than packed.
  const std::size_t packed = packed_bytes(n);
  const std::size_t rows = encode_rle(in, n, true, out.data.items, packed - 1);
  const std::size_t rle =
      encode_rle(in, n, false, out.data.items, rows > 0 ? rows - 1 : packed - 1);
  if (rle > 0) {
    out.encoding = msg::MapPatchEncoding::kRunLength;
    out.data.count = static_cast<std::uint16_t>(rle);
  } else if (rows > 0) {
    (void)encode_rle(in, n, true, out.data.items, rows);  // overwritten by the attempt above
    out.encoding = msg::MapPatchEncoding::kRowDelta;
    out.data.count = static_cast<std::uint16_t>(rows);
  } else {
    encode_packed(in, n, out.data.items);
    out.encoding = msg::MapPatchEncoding::kPacked2Bit;
    out.data.count = static_cast<std::uint16_t>(packed);
  }
  std::fill(out.data.items + out.data.count, out.data.items + limits::kMaxPatchBytes,
            std::uint8_t{0});
  return Status::ok();
}

Status decode_patch(const msg::MapPatch& in, PatchCells& out) {
  if (!valid_size(in.width_cells, in.height_cells)) {
    return {Errc::kInvalidArgument, "patch size out of range"};
  }
  if (in.data.count > limits::kMaxPatchBytes)
    return {Errc::kInvalidArgument, "patch payload too long"};
  const auto n = static_cast<std::size_t>(in.width_cells) * in.height_cells;
  // Decode into a scratch copy so `out` is never left half-written.
  static_assert(limits::kMaxPatchCells <= 4096, "scratch lives on the stack");
  PatchCells scratch;
  Status s{Errc::kInvalidArgument, "unknown patch encoding"};
  switch (in.encoding) {
    case msg::MapPatchEncoding::kPacked2Bit:
      s = decode_packed(in, n, scratch);
      break;
    case msg::MapPatchEncoding::kRunLength:
      s = decode_rle(in, n, false, scratch);
      break;
    case msg::MapPatchEncoding::kRowDelta:
      s = decode_rle(in, n, true, scratch);
      break;
  }
  if (!s) return s;
  scratch.width = in.width_cells;
  scratch.height = in.height_cells;
  out = scratch;
  return Status::ok();
}

}  // namespace colag
