// Map patches as a UGV receives them: header fields and payload from the input, through the
// codec and MapStore::apply. Invariants: a patch that decodes re-encodes to the same cells; an
// applied patch leaves exactly its cells in the map; a rejected one changes nothing.
#include <cstring>

#include "colag/common/map_patch_codec.hpp"
#include "colag/common/map_store.hpp"
#include "fuzz_input.hpp"

using colag::CellIndex;
using colag::CellState;
using colag::MapStore;
using colag::PatchCells;
using colag::fuzz::FuzzInput;

// Input: encoding u8, width u16, height u16, origin cell x/y i16, flags u8, then the payload.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static MapStore store;  // large (the whole world grid): one for the process, like a UGV's
  static PatchCells decoded;
  static PatchCells again;
  static colag::msg::MapPatch reencoded;

  FuzzInput in(data, size);
  colag::msg::MapPatch patch;
  patch.encoding = static_cast<colag::msg::MapPatchEncoding>(in.u8());
  patch.width_cells = in.u16();
  patch.height_cells = in.u16();
  const auto cx = static_cast<std::int16_t>(in.u16());
  const auto cy = static_cast<std::int16_t>(in.u16());
  const std::uint8_t flags = in.u8();
  const auto& g = store.geometry();
  patch.resolution_m = (flags & 1) ? 0.2 : g.resolution();
  patch.origin_x_m = g.origin_x() + cx * g.resolution() + ((flags & 2) ? 0.05 : 0.0);
  patch.origin_y_m = (flags & 4) ? __builtin_nan("") : g.origin_y() + cy * g.resolution();
  const std::size_t n = std::min(in.remaining(), sizeof(patch.data.items));
  std::memcpy(patch.data.items, in.rest(), n);
  patch.data.count = static_cast<std::uint16_t>(n);

  if (colag::decode_patch(patch, decoded)) {
    COLAG_FUZZ_CHECK(decoded.width == patch.width_cells && decoded.height == patch.height_cells);
    COLAG_FUZZ_CHECK(colag::encode_patch(decoded, reencoded));
    // The encoder sends the smallest encoding; no valid payload is shorter than canonical.
    COLAG_FUZZ_CHECK(reencoded.data.count <= n);
    COLAG_FUZZ_CHECK(colag::decode_patch(reencoded, again));
    for (int i = 0; i < decoded.width * decoded.height; ++i)
      COLAG_FUZZ_CHECK(again.cells[static_cast<std::size_t>(i)] ==
                       decoded.cells[static_cast<std::size_t>(i)]);
  }

  const auto before = store.counters();
  const CellIndex probe{cx, cy};
  const CellState probe_before = store.state(probe);
  if (store.apply(patch)) {
    COLAG_FUZZ_CHECK(store.counters().patches_applied == before.patches_applied + 1);
    // Every cell of it the map holds (a patch may reach past the map's edge).
    for (int y = 0; y < decoded.height; ++y)
      for (int x = 0; x < decoded.width; ++x)
        if (store.geometry().contains(colag::CellIndex{cx + x, cy + y}))
          COLAG_FUZZ_CHECK(store.state({cx + x, cy + y}) == decoded.at(x, y));
  } else {
    COLAG_FUZZ_CHECK(store.counters().patches_rejected == before.patches_rejected + 1);
    COLAG_FUZZ_CHECK(store.counters().cells_changed == before.cells_changed);
    COLAG_FUZZ_CHECK(store.state(probe) == probe_before);
  }
  return 0;
}
