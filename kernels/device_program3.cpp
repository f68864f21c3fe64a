#include "kernels/device_program3.h"

namespace meshd::gpu {
namespace {

template <typename T>
void upload_vector(DeviceBuffer<T>& to, const std::vector<T>& from, cudaStream_t stream) {
  to.upload(from.data(), from.size(), stream);
}

}  // namespace

void DeviceProgram3::upload(const Program3& program, cudaStream_t stream) {
  upload_vector(code_, program.code, stream);
  upload_vector(params_, program.params, stream);

  profiles_.resize(program.profiles.size());
  std::vector<ProgramView> profile_views;
  for (size_t k = 0; k < program.profiles.size(); ++k) {
    const Program& from = *program.profiles[k];
    Profile& to = profiles_[k];
    upload_vector(to.code, from.code, stream);
    upload_vector(to.params, from.params, stream);
    upload_vector(to.nodes, from.nodes, stream);
    upload_vector(to.samples, from.samples, stream);
    profile_views.push_back({to.code.data(), static_cast<uint32_t>(from.code.size()),
                             to.params.data(), to.nodes.data(), to.samples.data()});
  }
  upload_vector(profile_views_, profile_views, stream);

  surfaces_.resize(program.surfaces.size());
  std::vector<TriangleSurface3View> surface_views;
  for (size_t k = 0; k < program.surfaces.size(); ++k) {
    const TriangleSurface3& from = *program.surfaces[k];
    Surface& to = surfaces_[k];
    upload_vector(to.vertices, from.vertices, stream);
    upload_vector(to.vertex_normals, from.vertex_normals, stream);
    upload_vector(to.triangles, from.triangles, stream);
    upload_vector(to.triangle_normals, from.triangle_normals, stream);
    upload_vector(to.nodes, from.nodes, stream);
    surface_views.push_back({to.vertices.data(), to.vertex_normals.data(), to.triangles.data(),
                             to.triangle_normals.data(), to.nodes.data(), from.root});
  }
  upload_vector(surface_views_, surface_views, stream);
  // The host vectors of views above must outlive their copies.
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  view_ = {code_.data(), static_cast<uint32_t>(program.code.size()), params_.data(),
           profile_views_.data(), surface_views_.data()};
}

void DeviceSizeField3::upload(const CompiledSizeField3* field, cudaStream_t stream) {
  graded_ = field != nullptr;
  if (field == nullptr) {
    view_ = {nullptr, 0, INFINITY, 1.0};
    return;
  }
  programs_.resize(field->terms.size());
  std::vector<DistanceSizeView3> terms;
  for (size_t k = 0; k < field->terms.size(); ++k) {
    const CompiledSizeField3::Term& t = field->terms[k];
    programs_[k].upload(t.program, stream);
    terms.push_back({programs_[k].view(), t.h_min, t.slope, t.h_max});
  }
  terms_.upload(terms.data(), terms.size(), stream);
  MESHD_CUDA_CHECK(cudaStreamSynchronize(stream));
  view_ = {terms_.data(), static_cast<uint32_t>(terms.size()), field->uniform, field->divisor};
}

}  // namespace meshd::gpu
