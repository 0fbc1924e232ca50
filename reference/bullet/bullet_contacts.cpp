#include "boxpile/reference/bullet/bullet_contacts.hpp"

#include <map>
#include <memory>
#include <utility>

#include "boxpile/reference/bullet/bullet_support.hpp"
#include "boxpile/reference/convention.hpp"

namespace boxpile {

using namespace reference_detail;

namespace {

// A collision configuration and dispatcher, kept for the process: building them allocates
// Bullet's pools. Each query makes a fresh algorithm (with its own persistent manifold), runs it
// once, reads the manifold and frees the algorithm.
class BulletQueryContext {
 public:
  explicit BulletQueryContext(const BulletPlaneOptions& plane) : dispatcher_(&config_) {
    if (plane.perturbation_iterations > 0) {
      // Changes the create function the dispatcher already holds a pointer to.
      config_.setPlaneConvexMultipointIterations(plane.perturbation_iterations, plane.minimum_points);
    }
  }

  // Contacts between shape a at ta and shape b at tb, as Bullet's solver would get them.
  // `kind_of` gives the feature kind of a normal (from B toward A).
  template <class KindOf>
  Manifold collide(const btCollisionShape& a, const btTransform& ta, const btCollisionShape& b,
                   const btTransform& tb, KindOf kind_of) {
    btCollisionObject oa, ob;
    oa.setCollisionShape(const_cast<btCollisionShape*>(&a));
    oa.setWorldTransform(ta);
    ob.setCollisionShape(const_cast<btCollisionShape*>(&b));
    ob.setWorldTransform(tb);
    const btCollisionObjectWrapper wa(nullptr, &a, &oa, ta, -1, -1);
    const btCollisionObjectWrapper wb(nullptr, &b, &ob, tb, -1, -1);

    btCollisionAlgorithm* algorithm = dispatcher_.findAlgorithm(&wa, &wb, nullptr, BT_CONTACT_POINT_ALGORITHMS);
    btManifoldResult result(&wa, &wb);
    const btDispatcherInfo info;
    algorithm->processCollision(&wa, &wb, info, &result);

    Manifold out;
    btManifoldArray manifolds;
    algorithm->getAllContactManifolds(manifolds);
    for (int m = 0; m < manifolds.size(); ++m) {
      const btPersistentManifold& pm = *manifolds[m];
      const bool a_is_body0 = pm.getBody0() == &oa;
      for (int i = 0; i < pm.getNumContacts() && out.size() < kMaxManifoldPoints; ++i) {
        const btManifoldPoint& p = pm.getContactPoint(i);
        const Vec3 n = from_bt(a_is_body0 ? p.m_normalWorldOnB : -p.m_normalWorldOnB);
        out.push_back(contact_from_bullet(p, a_is_body0, kind_of(n)));
      }
    }
    algorithm->~btCollisionAlgorithm();
    dispatcher_.freeCollisionAlgorithm(algorithm);
    return out;
  }

 private:
  btDefaultCollisionConfiguration config_;
  btCollisionDispatcher dispatcher_;
};

BulletQueryContext& bullet_context(const BulletPlaneOptions& plane) {
  thread_local std::map<std::pair<int, int>, std::unique_ptr<BulletQueryContext>> contexts;
  const std::pair<int, int> key = plane.perturbation_iterations > 0
                                      ? std::pair{plane.perturbation_iterations, plane.minimum_points}
                                      : std::pair{0, 0};
  auto& slot = contexts[key];
  if (!slot) slot = std::make_unique<BulletQueryContext>(plane);
  return *slot;
}

btTransform transform_of(const OrientedBox& box) {
  return btTransform(to_bt(box.axes), to_bt(box.center));
}

}  // namespace

Manifold bullet_box_box(const OrientedBox& a, const OrientedBox& b) {
  const btBoxShape sa(to_bt(a.half));
  const btBoxShape sb(to_bt(b.half));
  return bullet_context({}).collide(sa, transform_of(a), sb, transform_of(b),
                                    [&](const Vec3& n) { return box_box_kind(a, b, n); });
}

Manifold bullet_box_plane(const OrientedBox& a, const HalfSpace& plane, const BulletPlaneOptions& options) {
  const btBoxShape sa(to_bt(a.half));
  const btStaticPlaneShape sp(to_bt(plane.normal), plane.offset);
  return bullet_context(options).collide(sa, transform_of(a), sp, btTransform::getIdentity(),
                                         [](const Vec3&) { return FeatureKind::Plane; });
}

}  // namespace boxpile
