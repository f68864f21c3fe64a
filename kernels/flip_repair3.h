// The Delaunay tetrahedralization a 3D GPU job keeps on the device between two retriangulations,
// and its repair by flips once the nodes have moved (issue 16's "repair by 3D flips where they
// succeed"): the rounds of core/delaunay/flip_rounds3.cuh as kernels, one launch per phase and
// one read of the round's counts. The host's FlipRepair3 (core/delaunay/flip_repair3.h) runs the
// same rounds and answers the same tetrahedra.
#pragma once

#include <cuda_runtime.h>

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/vec3.h"
#include "core/delaunay/flip_repair3.h"
#include "kernels/device_buffer.h"
#include "kernels/pinned_value.h"

namespace meshd::gpu {

class KeptTetrahedra3 {
 public:
  // FlipRepair3::keep on the device (the faces linked by a radix sort of their keys).
  bool keep(const std::vector<std::array<int32_t, 4>>& tets, int64_t nodes, cudaStream_t stream);
  void forget() { kept_ = false; }
  bool kept() const { return kept_; }
  // FlipRepair3::repair for the points `p` (#N, on the device, numbered as at keep).
  RepairOutcome3 repair(DeviceSpan<const Vec3> p, int max_rounds, cudaStream_t stream);
  // The live tetrahedra, in slot order (the host waits for the stream).
  std::vector<std::array<int32_t, 4>> download(cudaStream_t stream) const;

 private:
  FlipArrays3 arrays(DeviceSpan<const Vec3> p) const;
  // The keys of the slots' faces (unique ones for dead slots) sorted, with their face ids.
  void sort_face_keys(int64_t faces, cudaStream_t stream);
  // overfull_faces on the device (the host waits).
  int64_t count_overfull_faces(cudaStream_t stream);

  DeviceBuffer<Tet4> tets_;    // flip_capacity3 slots, of which slots_ used
  DeviceBuffer<int32_t> adj_;  // 4 per slot
  DeviceBuffer<uint64_t> keys_, sorted_keys_;
  DeviceBuffer<int32_t> faces_, sorted_faces_;
  DeviceBuffer<int32_t> third_, position_;
  DeviceBuffer<uint32_t> claim_;
  DeviceBuffer<uint8_t> turned_, kind_, new_slot_, temp_;
  DeviceBuffer<FlipCounts3> counts_;
  PinnedValue<FlipCounts3> h_counts_;
  int64_t slots_ = 0;
  bool kept_ = false;
};

}  // namespace meshd::gpu
