// slides: each listed body's centre ends `distance` from its start, within `tolerance` (both m):
// how far a box slides (or sticks) on an incline for its friction coefficient.
#include "boxpile/validation/stability/checks/check.hpp"

#include <cmath>

namespace boxpile {

using json_input::JsonNode;
namespace {

struct Slide {
  int body = 0;
  double distance = 0.0, tolerance = 0.0;
};

class SlidesCheck final : public Check {
 public:
  explicit SlidesCheck(std::vector<Slide> slides) : slides_(std::move(slides)), last_(slides_.size()) {}

  void observe(const RunView&, long, double, const std::vector<BodyState>& states) override {
    for (std::size_t k = 0; k < slides_.size(); ++k) last_[k] = states[static_cast<std::size_t>(slides_[k].body)].position;
  }
  void evaluate(const RunView& run, std::vector<SceneCheckResult>& out) const override {
    for (std::size_t k = 0; k < slides_.size(); ++k) {
      const std::size_t i = static_cast<std::size_t>(slides_[k].body);
      const double moved = (last_[k] - run.start[i]).norm();
      out.push_back(at_most("slide " + run.scene.bodies[i].name, std::abs(moved - slides_[k].distance),
                            slides_[k].tolerance, "m"));
    }
  }

 private:
  std::vector<Slide> slides_;
  std::vector<Vec3> last_;  // each slide's body position, last observed
};

std::unique_ptr<Check> read_slides(const std::optional<JsonNode>& node, const Scene& scene) {
  std::vector<Slide> slides;
  for (std::size_t i = 0; i < node->array_size(); ++i) {
    const JsonNode item = node->element(i);
    item.expect_object({"body", "distance", "tolerance"});
    slides.push_back({read_check_body(item.at("body"), scene), json_input::read_non_negative(item.at("distance")),
                      json_input::read_positive(item.at("tolerance"))});
  }
  return std::make_unique<SlidesCheck>(std::move(slides));
}

}  // namespace

const CheckRow& slides_check() {
  static const CheckRow row{"slides",
                            "each listed body's centre ends distance (m) from its start, within tolerance (m)", 70,
                            false, true, read_slides};
  return row;
}

}  // namespace boxpile
