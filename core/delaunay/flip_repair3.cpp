#include "core/delaunay/flip_repair3.h"

#include <algorithm>
#include <cstring>
#include <utility>

namespace meshd {

int64_t overfull_faces(const uint64_t* keys, int64_t n) {
  int64_t over = 0;
  for (int64_t i = 2; i < n; ++i) over += keys[i] == keys[i - 2];
  return over;
}

RepairOutcome3 repair_outcome3(const FlipCounts3& last, bool ended, int rounds, int64_t flips,
                               int64_t overfull) {
  RepairOutcome3 out;
  out.overfull = overfull;
  out.rounds = rounds;
  out.flips = flips;
  out.ended = ended;
  if (ended) {
    out.inverted = last.inverted;
    out.stuck = last.stuck;
  }
  return out;
}

std::vector<std::array<int32_t, 4>> take_turned3(const std::vector<Vec3>& points,
                                                 std::vector<std::array<int32_t, 4>>& tets) {
  std::vector<std::array<int32_t, 4>> turned;
  const auto positive = [&](const std::array<int32_t, 4>& t) {
    return orientation3_filtered(points[t[0]], points[t[1]], points[t[2]], points[t[3]]) == 1;
  };
  const auto end = std::stable_partition(tets.begin(), tets.end(), positive);
  turned.assign(end, tets.end());
  tets.erase(end, tets.end());
  return turned;
}

bool FlipRepair3::keep(const std::vector<std::array<int32_t, 4>>& tets, int64_t nodes) {
  kept_ = false;
  if (nodes >= (int64_t{1} << kFaceKeyBits)) return false;
  const auto m = static_cast<int64_t>(tets.size());
  const int64_t capacity = flip_capacity3(m);
  tets_.resize(capacity);
  std::memcpy(tets_.data(), tets.data(), m * sizeof(Tet4));
  adj_.assign(4 * capacity, -1);
  // Equal keys are a face's two sides; a key alone is on the hull.
  std::vector<std::pair<uint64_t, int32_t>> faces(4 * m);
  for (int64_t i = 0; i < 4 * m; ++i)
    faces[i] = {flip3::face_key_of(tets_[i >> 2], static_cast<int>(i & 3)),
                static_cast<int32_t>(i)};
  std::sort(faces.begin(), faces.end());
  for (size_t i = 0; i + 1 < faces.size(); ++i)
    if (faces[i].first == faces[i + 1].first) {
      adj_[faces[i].second] = faces[i + 1].second;
      adj_[faces[i + 1].second] = faces[i].second;
      ++i;
    }
  third_.assign(4 * capacity, -1);
  position_.assign(4 * capacity, 0);
  kind_.assign(4 * capacity, 0);
  new_slot_.assign(4 * capacity, 0);
  claim_.assign(capacity, 0);
  turned_.assign(capacity, 0);
  slots_ = m;
  kept_ = true;
  return true;
}

RepairOutcome3 FlipRepair3::repair(const std::vector<Vec3>& points, int max_rounds) {
  if (!kept_) return {};
  FlipCounts3 counts{};
  const FlipArrays3 a{tets_.data(),  adj_.data(),   turned_.data(),   kind_.data(),
                      third_.data(), claim_.data(), new_slot_.data(), position_.data(),
                      points.data(), &counts};
  int rounds = 0;
  int64_t flips = 0;
  bool ended = false;
  while (rounds < max_rounds) {
    const int64_t faces = 4 * slots_;
    counts = FlipCounts3{};
    std::fill(claim_.begin(), claim_.begin() + slots_, UINT32_MAX);
    for (int64_t t = 0; t < slots_; ++t) mark_turned(a, t);
    for (int64_t t = 0; t < slots_; ++t) mark_beside_turned(a, t);
    for (int64_t i = 0; i < faces; ++i) propose_flip(a, i);
    for (int64_t i = 0; i < faces; ++i) settle_winner(a, i);
    int32_t sum = 0;
    for (int64_t i = 0; i < faces; ++i) {
      position_[i] = sum;
      sum += new_slot_[i];
    }
    ++rounds;
    if (counts.flips == 0) {
      ended = true;
      break;
    }
    if (slots_ + counts.new_slots > static_cast<int64_t>(tets_.size())) break;
    for (int64_t i = 0; i < faces; ++i) apply_flip(a, i, slots_);
    slots_ += counts.new_slots;
    flips += counts.flips;
  }
  int64_t overfull = 0;
  if (flips > 0) {
    std::vector<uint64_t> keys;
    keys.reserve(4 * slots_);
    for (int64_t t = 0; t < slots_; ++t)
      if (tets_[t].v[0] >= 0)
        for (int f = 0; f < 4; ++f) keys.push_back(flip3::face_key_of(tets_[t], f));
    std::sort(keys.begin(), keys.end());
    overfull = overfull_faces(keys.data(), static_cast<int64_t>(keys.size()));
  }
  const RepairOutcome3 out = repair_outcome3(counts, ended, rounds, flips, overfull);
  if (!out.usable()) kept_ = false;
  return out;
}

std::vector<std::array<int32_t, 4>> FlipRepair3::tets() const {
  std::vector<std::array<int32_t, 4>> out;
  out.reserve(slots_);
  for (int64_t t = 0; t < slots_; ++t)
    if (tets_[t].v[0] >= 0)
      out.push_back({tets_[t].v[0], tets_[t].v[1], tets_[t].v[2], tets_[t].v[3]});
  return out;
}

}  // namespace meshd
