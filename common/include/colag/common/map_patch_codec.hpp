#pragma once
// The map-patch codec shared by the UAV (encoder) and the UGVs (decoder). A patch is a
// width x height window of ground-level cells, each free / occupied / unknown, row-major from
// the (x, y)-minimum corner. Two encodings; the encoder sends whichever is smaller:
// - kPacked2Bit: 4 cells per byte, cell i in bits 2*(i%4)..+1 (value 3 invalid, padding 0);
// - kRunLength: runs of one state; each run is a varint (state | (length-1) << 2): 7 bits per
//   byte, high bit = more bytes follow. Maps are mostly long free runs: a few bytes per row.
// - kRowDelta: the same runs over each cell XOR the cell one row below (row 0: XOR free).
//   A box then costs runs only where it starts and ends, not on every row it spans.
// The decoder validates everything (sizes, lengths, values, trailing bytes) and writes its
// output only on success.
#include <array>
#include <cstdint>

#include "colag/common/limits.hpp"
#include "colag/common/status.hpp"
#include "colag/msg/map_patch.hpp"

namespace colag {

enum class CellState : std::uint8_t { kFree = 0, kOccupied = 1, kUnknown = 2 };

struct PatchCells {
  int width = 0;
  int height = 0;
  std::array<CellState, limits::kMaxPatchCells> cells{};  // row-major, width * height used

  CellState at(int x, int y) const { return cells[static_cast<std::size_t>(y) * width + x]; }
};

// Writes width, height, encoding and data of `out` (the caller sets the rest).
Status encode_patch(const PatchCells& in, msg::MapPatch& out);
// Decodes and validates the payload of `in`; `out` is untouched on failure.
Status decode_patch(const msg::MapPatch& in, PatchCells& out);

}  // namespace colag
