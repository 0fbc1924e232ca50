// A collider for `boxpile conform` in C++ (docs/conform.md): reads one query per line, answers
// with one line. It answers with boxpile's own detector: replace `collide` with your own.
#include <boxpile/boxpile.hpp>
#include <boxpile/validation/core/json_output.hpp>

#include <iostream>
#include <string>

namespace {

boxpile::Manifold collide(const boxpile::ContactQuery& q) {
  const boxpile::OrientedBox a = boxpile::OrientedBox::from(q.a.pose, q.a.half_extents);
  boxpile::Manifold m;
  if (q.plane) {
    boxpile::collide_box_plane(a, *q.plane, 0.0, m);
  } else {
    boxpile::collide_box_box(a, boxpile::OrientedBox::from(q.b->pose, q.b->half_extents), {}, m);
  }
  return m;
}

}  // namespace

int main() {
  std::string line;
  for (int n = 1; std::getline(std::cin, line); ++n) {
    const boxpile::ContactQuery q = boxpile::parse_query(line, "line " + std::to_string(n));
    std::cout << boxpile::answer_json(collide(q)).dump() << std::endl;  // endl: flushed at once
  }
}
