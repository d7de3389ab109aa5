// The frame profile as files people and tools read: a statistics document (--stats-json)
// and a Chrome trace-event timeline (--trace) that opens in Perfetto and chrome://tracing.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "renderer/render/render.h"

namespace tessera {

// The --stats-json schema documented in docs/load-balancing.md; raise it when a field is
// renamed, removed or changes meaning (adding a field keeps it).
constexpr int kStatsSchemaVersion = 1;

// Everything in the profile, under "schema_version": the frame's load balance, each thread, each wave, each tile's
// summed cost and, when recorded, every tile run (thread, start, end, samples, rays).
nlohmann::json stats_json(const FrameProfile& profile, const RenderStats& stats);

// One track per thread, one complete ('X') slice per tile run named "tile C,R wave W",
// times in microseconds since the frame started. Needs the tile records.
nlohmann::json trace_json(const FrameProfile& profile);

// Both write atomically (file_output.h) and throw OutputError.
void write_stats_json(const std::string& path, const FrameProfile& profile, const RenderStats& stats);
void write_trace_json(const std::string& path, const FrameProfile& profile);

}  // namespace tessera
