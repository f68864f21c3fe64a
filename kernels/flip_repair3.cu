// flip_repair3.h: the faces linked by a sort of their keys, then per round one kernel for each
// phase of flip_rounds3.cuh and a scan for the new slots.
#include <algorithm>

#include "kernels/cuda_check.h"
#include "kernels/flip_repair3.h"
#include "kernels/launch.h"
#include "kernels/scan.h"
#include "kernels/thread_index.cuh"

namespace meshd::gpu {
namespace {

__global__ void face_keys(DeviceSpan<const Tet4> tets, int64_t faces, DeviceSpan<uint64_t> keys,
                          DeviceSpan<int32_t> ids) {
  const int64_t i = thread_index();
  if (i >= faces) return;
  keys[i] = flip3::slot_face_key(tets[i >> 2], i);
  ids[i] = static_cast<int32_t>(i);
}

// Equal keys are a face's two sides; a key alone is on the hull (adj stays -1).
__global__ void link_faces(DeviceSpan<const uint64_t> keys, DeviceSpan<const int32_t> ids,
                           int64_t faces, DeviceSpan<int32_t> adj) {
  const int64_t i = thread_index();
  if (i + 1 >= faces || keys[i] != keys[i + 1]) return;
  if (i > 0 && keys[i - 1] == keys[i]) return;
  adj[ids[i]] = ids[i + 1];
  adj[ids[i + 1]] = ids[i];
}

__global__ void count_overfull(DeviceSpan<const uint64_t> keys, int64_t faces, int32_t* over) {
  const int64_t i = thread_index();
  if (i >= 2 && i < faces && keys[i] == keys[i - 2]) atomicAdd(over, 1);
}

__global__ void mark_turned_tets(FlipArrays3 a, int64_t slots) {
  const int64_t t = thread_index();
  if (t < slots) mark_turned(a, t);
}

__global__ void mark_beside_turned_tets(FlipArrays3 a, int64_t slots) {
  const int64_t t = thread_index();
  if (t < slots) mark_beside_turned(a, t);
}

__global__ void propose_flips(FlipArrays3 a, int64_t faces) {
  const int64_t i = thread_index();
  if (i < faces) propose_flip(a, i);
}

__global__ void settle_winners(FlipArrays3 a, int64_t faces) {
  const int64_t i = thread_index();
  if (i < faces) settle_winner(a, i);
}

__global__ void apply_flips(FlipArrays3 a, int64_t faces, int64_t base) {
  const int64_t i = thread_index();
  if (i < faces) apply_flip(a, i, base);
}

}  // namespace

FlipArrays3 KeptTetrahedra3::arrays(DeviceSpan<const Vec3> p) const {
  return {tets_.data(),  adj_.data(),      turned_.data(),   kind_.data(), third_.data(),
          claim_.data(), new_slot_.data(), position_.data(), p.data,       counts_.data()};
}

void KeptTetrahedra3::sort_face_keys(int64_t faces, cudaStream_t stream) {
  keys_.resize(faces);
  sorted_keys_.resize(faces);
  faces_.resize(faces);
  sorted_faces_.resize(faces);
  face_keys<<<blocks_for(faces), kBlock, 0, stream>>>(tets_.span(), faces, keys_.span(),
                                                      faces_.span());
  MESHD_CHECK_LAUNCH("face_keys");
  sort_pairs(keys_.data(), sorted_keys_.data(), faces_.data(), sorted_faces_.data(), faces, 64,
             temp_, stream);
}

int64_t KeptTetrahedra3::count_overfull_faces(cudaStream_t stream) {
  const int64_t faces = 4 * slots_;
  sort_face_keys(faces, stream);
  MESHD_CUDA_CHECK(cudaMemsetAsync(counts_.data(), 0, sizeof(FlipCounts3), stream));
  count_overfull<<<blocks_for(faces), kBlock, 0, stream>>>(sorted_keys_.span(), faces,
                                                           &counts_.data()->overfull);
  MESHD_CHECK_LAUNCH("count_overfull");
  MESHD_CUDA_CHECK(cudaMemcpyAsync(h_counts_.get(), counts_.data(), sizeof(FlipCounts3),
                                   cudaMemcpyDeviceToHost, stream));
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  return h_counts_.get()->overfull;
}

bool KeptTetrahedra3::keep(const std::vector<std::array<int32_t, 4>>& tets, int64_t nodes,
                           cudaStream_t stream) {
  static_assert(sizeof(Tet4) == sizeof(tets[0]));
  kept_ = false;
  if (nodes >= (int64_t{1} << kFaceKeyBits)) return false;
  const auto m = static_cast<int64_t>(tets.size());
  const int64_t capacity = flip_capacity3(m);
  tets_.resize(capacity);
  adj_.resize(4 * capacity);
  claim_.resize(capacity);
  turned_.resize(capacity);
  for (auto* per_face : {&third_, &position_}) per_face->resize(4 * capacity);
  for (auto* per_face : {&kind_, &new_slot_}) per_face->resize(4 * capacity);
  counts_.resize(1);
  if (m > 0)
    MESHD_CUDA_CHECK(cudaMemcpyAsync(tets_.data(), tets.data(), m * sizeof(Tet4),
                                     cudaMemcpyHostToDevice, stream));
  const int64_t faces = 4 * m;
  MESHD_CUDA_CHECK(cudaMemsetAsync(adj_.data(), 0xff, adj_.size() * sizeof(int32_t), stream));
  if (faces > 0) {
    sort_face_keys(faces, stream);
    link_faces<<<blocks_for(faces), kBlock, 0, stream>>>(sorted_keys_.span(), sorted_faces_.span(),
                                                         faces, adj_.span());
    MESHD_CHECK_LAUNCH("link_faces");
  }
  // The copy reads the caller's vector.
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  slots_ = m;
  kept_ = true;
  return true;
}

RepairOutcome3 KeptTetrahedra3::repair(DeviceSpan<const Vec3> p, int max_rounds,
                                       cudaStream_t stream) {
  if (!kept_) return {};
  const FlipArrays3 a = arrays(p);
  FlipCounts3 last{};
  int rounds = 0;
  int64_t flips = 0;
  bool ended = false;
  while (rounds < max_rounds) {
    const int64_t faces = 4 * slots_;
    MESHD_CUDA_CHECK(cudaMemsetAsync(counts_.data(), 0, sizeof(FlipCounts3), stream));
    MESHD_CUDA_CHECK(cudaMemsetAsync(claim_.data(), 0xff, slots_ * sizeof(uint32_t), stream));
    if (slots_ > 0) {
      mark_turned_tets<<<blocks_for(slots_), kBlock, 0, stream>>>(a, slots_);
      MESHD_CHECK_LAUNCH("mark_turned_tets");
      mark_beside_turned_tets<<<blocks_for(slots_), kBlock, 0, stream>>>(a, slots_);
      MESHD_CHECK_LAUNCH("mark_beside_turned_tets");
      propose_flips<<<blocks_for(faces), kBlock, 0, stream>>>(a, faces);
      MESHD_CHECK_LAUNCH("propose_flips");
      settle_winners<<<blocks_for(faces), kBlock, 0, stream>>>(a, faces);
      MESHD_CHECK_LAUNCH("settle_winners");
      exclusive_scan(new_slot_.data(), position_.data(), faces, temp_, stream);
    }
    MESHD_CUDA_CHECK(cudaMemcpyAsync(h_counts_.get(), counts_.data(), sizeof(FlipCounts3),
                                     cudaMemcpyDeviceToHost, stream));
    MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
    last = *h_counts_.get();
    ++rounds;
    if (last.flips == 0) {
      ended = true;
      break;
    }
    if (slots_ + last.new_slots > static_cast<int64_t>(tets_.size())) break;
    apply_flips<<<blocks_for(faces), kBlock, 0, stream>>>(a, faces, slots_);
    MESHD_CHECK_LAUNCH("apply_flips");
    slots_ += last.new_slots;
    flips += last.flips;
  }
  int64_t overfull = 0;
  if (flips > 0) overfull = count_overfull_faces(stream);
  const RepairOutcome3 out = repair_outcome3(last, ended, rounds, flips, overfull);
  if (!out.usable()) kept_ = false;
  return out;
}

std::vector<std::array<int32_t, 4>> KeptTetrahedra3::download(cudaStream_t stream) const {
  std::vector<std::array<int32_t, 4>> all(static_cast<size_t>(slots_));
  if (slots_ > 0)
    MESHD_CUDA_CHECK(cudaMemcpyAsync(all.data(), tets_.data(), slots_ * sizeof(Tet4),
                                     cudaMemcpyDeviceToHost, stream));
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  all.erase(std::remove_if(all.begin(), all.end(),
                           [](const std::array<int32_t, 4>& t) { return t[0] < 0; }),
            all.end());
  return all;
}

}  // namespace meshd::gpu
