// A compiled 3D geometry (program3d.h) and size field (size_field3.h) copied whole to the device:
// the instructions and parameters, and the 2D profiles and triangle surfaces they point at, so
// that device code evaluates them through the same views as the host (sdf3_eval.cuh,
// size_field3_eval.cuh). Buffers are kept and reused by the next upload.
#pragma once

#include <cuda_runtime.h>

#include <vector>

#include "core/geometry/program.h"
#include "core/geometry3d/program3d.h"
#include "core/geometry3d/size_field3.h"
#include "kernels/device_buffer.h"

namespace meshd::gpu {

class DeviceProgram3 {
 public:
  // Copies `program`; returns once the copies are done (the host views it builds are gone then).
  void upload(const Program3& program, cudaStream_t stream);
  // Valid on the device until the next upload.
  Program3View view() const { return view_; }

 private:
  struct Profile {
    DeviceBuffer<Instruction> code;
    DeviceBuffer<double> params;
    DeviceBuffer<BvhNode> nodes;
    DeviceBuffer<float> samples;
  };
  struct Surface {
    DeviceBuffer<Vec3> vertices, vertex_normals, triangle_normals;
    DeviceBuffer<int32_t> triangles;
    DeviceBuffer<SurfaceBvhNode> nodes;
  };
  DeviceBuffer<Instruction3> code_;
  DeviceBuffer<double> params_;
  std::vector<Profile> profiles_;
  DeviceBuffer<ProgramView> profile_views_;
  std::vector<Surface> surfaces_;
  DeviceBuffer<TriangleSurface3View> surface_views_;
  Program3View view_{};
};

class DeviceSizeField3 {
 public:
  // Copies `field` (null: the uniform field h = 1); returns once the copies are done.
  void upload(const CompiledSizeField3* field, cudaStream_t stream);
  SizeField3View view() const { return view_; }
  // False for the uniform field, which device code need not evaluate.
  bool graded() const { return graded_; }

 private:
  std::vector<DeviceProgram3> programs_;
  DeviceBuffer<DistanceSizeView3> terms_;
  SizeField3View view_{nullptr, 0, INFINITY, 1.0};
  bool graded_ = false;
};

}  // namespace meshd::gpu
