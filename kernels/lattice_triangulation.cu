// lattice_triangulation.h: flags, a scan, the triangles and links, the completion.
#include "core/distmesh/lattice_triangles.cuh"
#include "kernels/cuda_check.h"
#include "kernels/lattice_triangulation.h"
#include "kernels/scan.h"
#include "kernels/thread_index.cuh"

namespace meshd::gpu {
namespace {

struct LatticeCell {
  int64_t r, i;
  int s;
};

__device__ LatticeCell cell_of(const InitialGrid& g, int64_t id) {
  const int64_t cell = id / 2;
  return {cell / (g.nx - 1), cell % (g.nx - 1), static_cast<int>(id % 2)};
}

__global__ void flag_kept_triangles(InitialGrid g, DeviceSpan<const uint8_t> kept,
                                    DeviceSpan<uint8_t> in_u) {
  const int64_t id = thread_index();
  if (id >= in_u.size) return;
  const LatticeCell c = cell_of(g, id);
  const LatticeTriangle t = lattice_triangle(g, c.r, c.i, c.s);
  in_u[id] = kept[t.v[0]] && kept[t.v[1]] && kept[t.v[2]];
}

// A fixed point can sit near a triangle's centre, farther than step 2's exclusion radius from its
// corners: the triangles around it leave U.
__global__ void block_around_fixed(InitialGrid g, DeviceSpan<const Vec2> fixed,
                                   DeviceSpan<uint8_t> in_u) {
  const int64_t f = thread_index();
  if (f >= fixed.size) return;
  for_lattice_triangles_at(g, fixed[f],
                           [&](int64_t r, int64_t i, int s) { in_u[lattice_id(g, r, i, s)] = 0; });
}

__global__ void write_u(InitialGrid g, DeviceSpan<const uint8_t> in_u,
                        DeviceSpan<const int32_t> u_position,
                        DeviceSpan<const int32_t> kept_position, int64_t nfix, DeviceSpan<Tri> tris,
                        DeviceSpan<Tri> nbrs) {
  const int64_t id = thread_index();
  if (id >= in_u.size || !in_u[id]) return;
  const LatticeCell c = cell_of(g, id);
  const LatticeTriangle t = lattice_triangle(g, c.r, c.i, c.s);
  Tri tri, nbr;
  for (int k = 0; k < 3; ++k) {
    tri.v[k] = static_cast<int32_t>(nfix + kept_position[t.v[k]]);
    const int64_t across = lattice_neighbor(g, c.r, c.i, c.s, k);
    nbr.v[k] = across >= 0 && in_u[across] ? u_position[across] : -1;
  }
  tris[u_position[id]] = tri;
  nbrs[u_position[id]] = nbr;
}

}  // namespace

bool lattice_triangulation(const InitialGrid& grid, DeviceSpan<const uint8_t> kept,
                           DeviceSpan<const int32_t> kept_position, int64_t nfix,
                           DeviceSpan<const Vec2> p, DeviceBuffer<Tri>& tris,
                           DeviceBuffer<Tri>& nbrs, LatticeScratch& s, GapScratch& gaps,
                           DeviceBuffer<uint8_t>& temp, cudaStream_t stream) {
  const int64_t count = lattice_triangle_count(grid);
  s.in_u.resize(count);
  s.u_position.resize(count);
  int64_t in_u = 0;
  if (count > 0) {
    flag_kept_triangles<<<blocks_for(count), kBlock, 0, stream>>>(grid, kept, s.in_u.span());
    MESHD_CHECK_LAUNCH("flag_kept_triangles");
    if (nfix > 0) {
      block_around_fixed<<<blocks_for(nfix), kBlock, 0, stream>>>(
          grid, DeviceSpan<const Vec2>{p.data, nfix}, s.in_u.span());
      MESHD_CHECK_LAUNCH("block_around_fixed");
    }
    exclusive_scan(s.in_u.data(), s.u_position.data(), count, temp, stream);
    in_u = scan_total(s.u_position.data(), s.in_u.data(), count, stream);
  }
  tris.resize(in_u);
  nbrs.resize(in_u);
  if (in_u > 0) {
    write_u<<<blocks_for(count), kBlock, 0, stream>>>(
        grid, s.in_u.span(), s.u_position.span(), kept_position, nfix, tris.span(), nbrs.span());
    MESHD_CHECK_LAUNCH("write_u");
  }
  return complete_gaps(p, nfix, tris, nbrs, gaps, temp, stream);
}

}  // namespace meshd::gpu
