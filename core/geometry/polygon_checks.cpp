#include "core/geometry/polygon_checks.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <sstream>

#include "core/common/error.h"

namespace meshd {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// Sign of the turn a -> b -> c: +1 left, -1 right, 0 collinear. Exact (filtered), so that the
// sweep's order below stays consistent however close the edges come.
int orient(Vec2 a, Vec2 b, Vec2 c) {
  return static_cast<int>(CGAL::orientation(Kernel::Point_2(a.x, a.y), Kernel::Point_2(b.x, b.y),
                                            Kernel::Point_2(c.x, c.y)));
}

// The sweep order: by x, then by y (a vertical edge starts at its lower end).
bool lex_less(Vec2 a, Vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// For p collinear with a and b: whether p lies on the closed segment ab.
bool within(Vec2 a, Vec2 b, Vec2 p) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

std::string point_text(Vec2 p) {
  std::ostringstream out;
  out << "(" << p.x << ", " << p.y << ")";
  return out.str();
}

// Every message ends with what is allowed.
[[noreturn]] void fail(const std::string& path, const std::string& message) {
  throw_invalid(path + ".vertices",
                message +
                    "; a polygon must be simple: at least 3 distinct vertices, not all on one "
                    "line, its edges meeting only where neighbours share a vertex");
}

// ---------------------------------------------------------------------------------------------
// Local checks: count, finiteness, repeated vertices, collinearity, edges turning back.

void check_vertices(const std::vector<Vec2>& v, const std::string& path) {
  const size_t n = v.size();
  if (n < 3) fail(path, "a polygon needs at least 3 vertices (got " + std::to_string(n) + ")");
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i].x) || !std::isfinite(v[i].y)) {
      fail(path, "vertex " + std::to_string(i) + " " + point_text(v[i]) + " is not finite");
    }
  }

  // Equal vertices sit next to each other once sorted.
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return lex_less(v[a], v[b]) || (v[a] == v[b] && a < b); });
  for (size_t k = 0; k + 1 < n; ++k) {
    if (!(v[order[k]] == v[order[k + 1]])) continue;
    const size_t i = std::min(order[k], order[k + 1]), j = std::max(order[k], order[k + 1]);
    std::string message = "vertices " + std::to_string(i) + " and " + std::to_string(j) +
                          " are the same point " + point_text(v[i]);
    if (i == 0 && j == n - 1) message += "; do not repeat the first vertex at the end";
    fail(path, message);
  }

  // All on one line: the polygon has no inside. (Checked before the turn-back test below, which
  // would also fire, because "zero area" is the clearer message.)
  bool collinear = true;
  for (size_t i = 2; i < n && collinear; ++i) collinear = orient(v[0], v[1], v[i]) == 0;
  if (collinear) fail(path, "the polygon has zero area: all its vertices lie on one line");

  // Neighbouring edges may only share their vertex; collinear and pointing back means overlap.
  for (size_t i = 0; i < n; ++i) {
    const Vec2 a = v[(i + n - 1) % n], b = v[i], c = v[(i + 1) % n];
    if (orient(a, b, c) == 0 && dot(b - a, c - b) < 0) {
      fail(path, "edges " + std::to_string((i + n - 1) % n) + " and " + std::to_string(i) +
                     " overlap: the boundary turns back on itself at vertex " + std::to_string(i) +
                     " " + point_text(b) + " (edge i joins vertices i and i+1)");
    }
  }
}

// ---------------------------------------------------------------------------------------------
// The sweep (Shamos-Hoey): a vertical line moves left to right over the edge endpoints, keeping
// the edges it cuts in bottom-to-top order. If any two edges meet, then two edges that are
// neighbours in that order meet, and they became neighbours at an insertion or a removal; so
// testing neighbours at those moments finds a meeting pair if there is one. The order is only
// well defined while no edges meet, which holds up to the first meeting found.

struct Segment {
  int edge;    // i: from vertex i to vertex i+1
  Vec2 left;   // lexicographically smaller end
  Vec2 right;  // larger end
};

// Two edges meet where the sweep order needs them to be apart; carries them out of std::set.
struct Touch {
  int a, b;
};

class BelowOnSweep {
 public:
  explicit BelowOnSweep(const std::vector<Segment>& segments) : segments_(&segments) {}

  // Whether edge a lies below edge b on the sweep line (both cut it).
  bool operator()(int ia, int ib) const {
    if (ia == ib) return false;
    const Segment& a = (*segments_)[ia];
    const Segment& b = (*segments_)[ib];
    int o;
    if (a.left == b.left) {
      o = orient(a.left, a.right, b.right);  // neighbours leaving their shared vertex
    } else if (lex_less(b.left, a.left)) {
      o = -orient(b.left, b.right, a.left);  // a starts later: is its start above or below b?
    } else {
      o = orient(a.left, a.right, b.left);
    }
    // Both cut the sweep line and one starts on the other: they touch there.
    if (o == 0) throw Touch{a.edge, b.edge};
    return o > 0;
  }

 private:
  const std::vector<Segment>* segments_;
};

enum class Meeting { kNone, kCross, kTouch };

Meeting meet(const Segment& a, const Segment& b) {
  const int o1 = orient(a.left, a.right, b.left), o2 = orient(a.left, a.right, b.right);
  const int o3 = orient(b.left, b.right, a.left), o4 = orient(b.left, b.right, a.right);
  if (o1 * o2 < 0 && o3 * o4 < 0) return Meeting::kCross;
  if ((o1 == 0 && within(a.left, a.right, b.left)) ||
      (o2 == 0 && within(a.left, a.right, b.right)) ||
      (o3 == 0 && within(b.left, b.right, a.left)) ||
      (o4 == 0 && within(b.left, b.right, a.right))) {
    return Meeting::kTouch;
  }
  return Meeting::kNone;
}

// Where a and b meet, for the message: the crossing point, or an endpoint lying on the other.
Vec2 meeting_point(const Segment& a, const Segment& b) {
  for (const auto& [p, s] :
       {std::pair{a.left, b}, std::pair{a.right, b}, std::pair{b.left, a}, std::pair{b.right, a}}) {
    if (orient(s.left, s.right, p) == 0 && within(s.left, s.right, p)) return p;
  }
  const Vec2 da = a.right - a.left, db = b.right - b.left;
  const double t = cross(b.left - a.left, db) / cross(da, db);
  return a.left + t * da;
}

[[noreturn]] void fail_meeting(const std::string& path, const std::vector<Segment>& segments,
                               int ia, int ib) {
  const Segment& a = segments[std::min(ia, ib)];
  const Segment& b = segments[std::max(ia, ib)];
  const bool crossing = meet(a, b) == Meeting::kCross;
  fail(path, "edges " + std::to_string(a.edge) + " and " + std::to_string(b.edge) +
                 (crossing ? " cross near " : " touch at ") + point_text(meeting_point(a, b)) +
                 " (edge i joins vertices i and i+1)");
}

void sweep(const std::vector<Vec2>& v, const std::string& path) {
  const int n = static_cast<int>(v.size());
  std::vector<Segment> segments(n);
  for (int i = 0; i < n; ++i) {
    Vec2 a = v[i], b = v[(i + 1) % n];
    if (lex_less(b, a)) std::swap(a, b);
    segments[i] = {i, a, b};
  }
  auto neighbours = [n](int a, int b) { return (a + 1) % n == b || (b + 1) % n == a; };

  // Events: 2i is edge i's insertion, 2i+1 its removal. At a shared point, removals go first so
  // that consecutive edges are never both in the order at their shared vertex.
  std::vector<int> events(2 * n);
  std::iota(events.begin(), events.end(), 0);
  auto where = [&](int e) { return e % 2 == 0 ? segments[e / 2].left : segments[e / 2].right; };
  std::sort(events.begin(), events.end(), [&](int e, int f) {
    const Vec2 p = where(e), q = where(f);
    if (lex_less(p, q)) return true;
    if (lex_less(q, p)) return false;
    return (e % 2) > (f % 2);
  });

  std::set<int, BelowOnSweep> active{BelowOnSweep(segments)};
  std::vector<std::set<int, BelowOnSweep>::iterator> position(n, active.end());
  auto check = [&](int a, int b) {
    if (neighbours(a, b)) return;  // may only share their vertex: turn-backs are excluded above
    if (meet(segments[a], segments[b]) != Meeting::kNone) fail_meeting(path, segments, a, b);
  };

  try {
    for (int e : events) {
      const int s = e / 2;
      if (e % 2 == 0) {
        const auto it = active.insert(s).first;
        position[s] = it;
        if (it != active.begin()) check(*std::prev(it), s);
        if (std::next(it) != active.end()) check(s, *std::next(it));
      } else {
        const auto it = position[s];
        const auto above = std::next(it);
        if (it != active.begin() && above != active.end()) check(*std::prev(it), *above);
        active.erase(it);
      }
    }
  } catch (const Touch& t) {
    fail_meeting(path, segments, t.a, t.b);
  }
}

}  // namespace

void check_simple_polygon(const std::vector<Vec2>& vertices, const std::string& path) {
  check_vertices(vertices, path);
  sweep(vertices, path);
}

}  // namespace meshd
