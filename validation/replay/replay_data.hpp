// The data of a replay page: recordings of one scene in one or more engines packed compactly
// (little-endian float32, int16 and uint32 arrays in base64), the bodies' shapes, and marks on the
// timeline where engines first disagree. docs/viewer.md describes the format.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "boxpile/validation/core/recording.hpp"

namespace boxpile {

// A moment on the timeline with what happened there.
struct ReplayMark {
  double t = 0.0;  // s
  std::string label;
};

// Where the pairs of a compare report (report.json) first pass their position or orientation
// threshold, one mark per pair that does.
std::vector<ReplayMark> marks_from_report(const nlohmann::json& report);

// Bounds on what a page holds, so that a long run of a large pile still opens in a browser.
struct ReplayBudget {
  // Body states kept (frames x bodies, over all engines): beyond it, every k-th frame is kept.
  std::size_t body_states = 60000;  // 13 float32 each: about 4.2 MB of base64
  // Contact points kept (over all engines and kept frames): beyond it, contacts are kept on every
  // k-th frame only.
  std::size_t contact_points = 60000;  // 36 bytes each: about 2.9 MB of base64
};

// Packs `runs` (one scene: the first run's shapes are drawn) into the page's data.
nlohmann::json replay_data(const std::string& title, const std::vector<const Recording*>& runs,
                           const std::vector<ReplayMark>& marks, const ReplayBudget& budget = {});

// Checks a page's data (as read back from a report's replay.json): every key present with the
// right type and every packed array of the length its counts say. InputError naming `source` and
// the JSON path otherwise.
void check_replay_data(const nlohmann::json& data, const std::string& source);

// The packed numbers' encoding, exposed for tests.
std::string base64(const std::vector<unsigned char>& bytes);
std::optional<std::vector<unsigned char>> unbase64(const std::string& text);  // nullopt when malformed

}  // namespace boxpile
