// Uses boxpile through its installed package: a scene stepped in two engines, one contact query
// answered by our detector and ODE's and compared, and a small collider judged. Exits 1 when a
// result is not what boxpile promises.
#include <boxpile/boxpile.hpp>

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

namespace {

int failures = 0;

void expect(bool ok, const std::string& what) {
  std::cout << (ok ? "ok   " : "FAIL ") << what << '\n';
  if (!ok) ++failures;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: consumer FIXTURES_DIR (P/share/boxpile/fixtures)\n";
    return 2;
  }
  const std::string fixtures = argv[1];

  // A unit box resting on the ground, stepped 1 s: both engines keep it there, at rest.
  const boxpile::Scene scene = boxpile::load_scene(fixtures + "/scenes/box_at_rest.json");
  for (const char* name : {"own", "ode"}) {
    const std::unique_ptr<boxpile::Engine> engine = boxpile::make_engine(name, scene);
    for (int k = 0; k < 240; ++k) engine->step();
    std::vector<boxpile::BodyState> states;
    engine->body_states(states);
    expect(states.size() == 1 && std::abs(states[0].position.z() - 0.5) < 1e-2 && states[0].velocity.norm() < 1e-2,
           std::string(name) + ": the box rests on the ground");
  }

  // The same query through two detectors, and their difference.
  const boxpile::ContactQuery query = boxpile::load_query(fixtures + "/contacts/aligned_offset.json");
  const boxpile::Manifold own = boxpile::find_detector("own").detect(query, {});
  const boxpile::Manifold ode = boxpile::find_detector("ode").detect(query, {});
  const boxpile::ContactDiff diff = boxpile::diff_contacts(own, ode);
  expect(own.size() == 4 && ode.size() == 4 && *diff.normal_angle < 1e-8, "own and ODE agree on aligned_offset");

  // Our detector, judged as any collider would be.
  boxpile::CheckOptions options;
  options.samples = 200;
  const boxpile::CheckResult result = boxpile::check_collider(boxpile::detector_collider("own"), options);
  expect(result.within_gates() && result.failures.empty(), "check_collider finds our detector right");
  return failures == 0 ? 0 : 1;
}
