// Volume (3D) jobs through meshd.v1.MeshService on an in-process server: the stream, the
// result's tetrahedra read back and checked, the backend rules, cancellation.
#include <google/protobuf/text_format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "client/result_assembly.h"
#include "core/mesh3d/tet_validity.h"
#include "tests/server/test_server.h"

namespace meshd::testing {
namespace {

using namespace std::chrono_literals;

v1::MeshRequest parse(const std::string& text) {
  v1::MeshRequest request;
  EXPECT_TRUE(google::protobuf::TextFormat::ParseFromString(text, &request)) << text;
  return request;
}

// A box minus a ball, ~1,500 nodes: corners, edges and a curved face.
constexpr const char* kBoxMinusBall = R"(
  volume { geometry { difference {
    base { name: "box" box { min { x: -1 y: -1 z: -1 } max { x: 1 y: 1 z: 1 } } }
    subtract { name: "ball" sphere { radius: 0.5 } } } } }
  h0: 0.2)";

TEST(VolumeService, GenerateStreamsAValidTetrahedralMesh) {
  TestServer server;
  auto stub = server.stub();
  const StreamResult r = generate(*stub, parse(kBoxMinusBall));
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  ASSERT_TRUE(r.has_done);
  EXPECT_TRUE(r.checksum_ok);
  const auto kinds = r.kinds();
  EXPECT_EQ(kinds.front(), "queued");
  EXPECT_EQ(kinds[1], "started");
  EXPECT_EQ(kinds.back(), "done");
  EXPECT_EQ(r.done.backend(), v1::JobOptions::BACKEND_CPU);

  EXPECT_EQ(r.mesh.dimension(), 3u);
  const TetMesh mesh = cli::to_tet_mesh(r.mesh);
  EXPECT_EQ(static_cast<int64_t>(mesh.points.size()), r.done.nodes());
  EXPECT_EQ(static_cast<int64_t>(mesh.tets.size()), r.done.tetrahedra());
  EXPECT_EQ(static_cast<int64_t>(mesh.boundary_faces.size()), r.done.boundary_faces());
  EXPECT_EQ(r.done.triangles(), 0);
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_TRUE(report.valid()) << (report.problems.empty() ? "" : report.problems[0]);
  EXPECT_EQ(mesh.boundary_names, (std::vector<std::string>{"box", "ball"}));
  // 8 - (4/3) pi 0.5^3 = 7.476; the ball's facets cut a little off it.
  EXPECT_NEAR(r.done.quality().volume(), 7.476, 0.05);
  EXPECT_GT(r.done.quality().q_min(), 0.2);
  EXPECT_GT(r.done.quality().min_dihedral_deg(), 10.0);
  EXPECT_GT(r.done.stats().fixed_nodes(), 8);
  // Full triangulations are those that did not just move a few nodes; their time and the steps'
  // are parts of the job's.
  const v1::RunStats& stats = r.done.stats();
  EXPECT_GE(stats.full_triangulations(), 1);
  EXPECT_LE(stats.full_triangulations(), stats.retriangulations());
  EXPECT_GT(stats.t_triangulation(), 0.0);
  EXPECT_GT(stats.t_forces(), 0.0);
  EXPECT_LT(stats.t_triangulation() + stats.t_forces() + stats.t_slivers(), stats.t_mesh());
  // The surface's nodes on the box or the ball within 1e-3 h0, by the exact distance here.
  double farthest = 0.0;
  for (const auto& f : mesh.boundary_faces)
    for (int32_t v : f) {
      const Vec3 p = mesh.points[v];
      const double box = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}) - 1.0;
      farthest = std::max(farthest, std::fabs(std::max(box, 0.5 - norm(p))));
    }
  EXPECT_LT(farthest, 1e-3 * 0.2);
  EXPECT_NEAR(r.done.quality().max_surface_offset(), farthest, 1e-9);
}

// A volume's snapshots: the nodes by 3 and the kept tetrahedra, which the first snapshot and
// every one after a retriangulation carry; each snapshot's points fit the tetrahedra held.
TEST(VolumeService, SnapshotsCarryTheNodesAndTheirTetrahedra) {
  TestServer server;
  auto stub = server.stub();
  v1::MeshRequest request = parse(kBoxMinusBall);
  request.mutable_options()->set_snapshot_every(3);
  const StreamResult r = generate(*stub, request);
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  ASSERT_TRUE(r.has_done);
  int snapshots = 0, carrying = 0;
  std::vector<int32_t> tets;
  for (const v1::MeshEvent& e : r.events) {
    if (!e.has_snapshot()) continue;
    const v1::Snapshot& s = e.snapshot();
    ++snapshots;
    EXPECT_EQ(s.iteration() % 3, 0);
    EXPECT_EQ(s.dimension(), 3u);
    EXPECT_FALSE(s.has_triangles());
    EXPECT_EQ(s.points_size() % 3, 0);
    if (snapshots == 1) {
      EXPECT_TRUE(s.has_tetrahedra()) << "the first snapshot has none";
    }
    if (s.has_tetrahedra()) {
      ++carrying;
      tets.assign(s.tetrahedra().begin(), s.tetrahedra().end());
    }
    ASSERT_FALSE(tets.empty());
    EXPECT_EQ(tets.size() % 4, 0u);
    const int nodes = s.points_size() / 3;
    EXPECT_TRUE(
        std::all_of(tets.begin(), tets.end(), [&](int32_t v) { return v >= 0 && v < nodes; }))
        << "snapshot " << s.iteration();
  }
  EXPECT_GT(snapshots, 2);
  EXPECT_GE(carrying, 1);
  EXPECT_LT(carrying, snapshots) << "every snapshot carried the tetrahedra again";
}

// A request whose surface settling once left a node 0.53 h0 inside the ball's face: at this h0
// the lattice-like corner of the cube minus a ball put it where two mirror-image tetrahedra
// would lie flat with it on the surface, until their interior nodes step aside
// (settle_surface3d.cpp).
TEST(VolumeService, EverySurfaceNodeSettlesOnTheBoundary) {
  TestServer server;
  auto stub = server.stub();
  const double h0 = 0.10184;
  const StreamResult r = generate(*stub, parse(R"(
  volume { geometry { difference {
    base { name: "box" box { min { x: -1 y: -1 z: -1 } max { x: 1 y: 1 z: 1 } } }
    subtract { name: "ball" sphere { radius: 0.5 } } } } }
  h0: )" + std::to_string(h0)));
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  ASSERT_TRUE(r.has_done);
  const TetValidityReport report = check_tet_validity(cli::to_tet_mesh(r.mesh));
  EXPECT_TRUE(report.valid()) << (report.problems.empty() ? "" : report.problems[0]);
  EXPECT_LT(r.done.quality().max_surface_offset(), 1e-3 * h0);
  EXPECT_GT(r.done.quality().min_dihedral_deg(), 10.0);
}

// The same part with its cube given as a closed triangle surface.
constexpr const char* kPolyhedronMinusBall = R"(
  volume { geometry { difference {
    base { name: "box" polyhedron {
      vertices: [-1, -1, -1, 1, -1, -1, -1, 1, -1, 1, 1, -1, -1, -1, 1, 1, -1, 1, -1, 1, 1, 1, 1, 1]
      triangles: [0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                  2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5] } }
    subtract { name: "ball" sphere { radius: 0.5 } } } } }
  h0: 0.2)";

TEST(VolumeService, APolyhedronMeshesAsTheBoxItDescribes) {
  TestServer server;
  auto stub = server.stub();
  const StreamResult box = generate(*stub, parse(kBoxMinusBall));
  const StreamResult poly = generate(*stub, parse(kPolyhedronMinusBall));
  ASSERT_TRUE(poly.status.ok()) << poly.status.error_message();
  ASSERT_TRUE(poly.has_done);
  const TetMesh mesh = cli::to_tet_mesh(poly.mesh);
  const TetValidityReport report = check_tet_validity(mesh);
  EXPECT_TRUE(report.valid()) << (report.problems.empty() ? "" : report.problems[0]);
  EXPECT_EQ(mesh.boundary_names, (std::vector<std::string>{"box", "ball"}));
  // The same sharp features, the same volume, the same quality as the box's.
  EXPECT_EQ(poly.done.stats().fixed_nodes(), box.done.stats().fixed_nodes());
  EXPECT_NEAR(poly.done.quality().volume(), box.done.quality().volume(), 0.01);
  EXPECT_GT(poly.done.quality().q_min(), 0.2);
  EXPECT_GT(poly.done.quality().min_dihedral_deg(), 10.0);
  EXPECT_LT(poly.done.quality().max_surface_offset(), 1e-3 * 0.2);
}

TEST(VolumeService, BadVolumesAndTheGpuBackendAreRefused) {
  TestServer server;
  auto stub = server.stub();
  const StreamResult bad =
      generate(*stub, parse("volume { geometry { sphere { radius: 0 } } } h0: 0.1"));
  EXPECT_EQ(bad.status.error_code(), grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(bad.status.error_message().find("volume.geometry.sphere.radius"), std::string::npos)
      << bad.status.error_message();
  v1::MeshRequest gpu = parse(kBoxMinusBall);
  gpu.mutable_options()->set_backend(v1::JobOptions::BACKEND_GPU);
  EXPECT_EQ(generate(*stub, gpu).status.error_code(), grpc::StatusCode::FAILED_PRECONDITION);
}

TEST(VolumeService, CancelStopsARunningVolumeJob) {
  TestServer server;
  auto stub = server.stub();
  v1::MeshRequest endless = parse(
      "volume { geometry { sphere { radius: 1 } } } h0: 0.2 "
      "params { dptol: 1e-12 max_iterations: 1000000 density_control_interval: 0 }");
  grpc::ClientContext context;
  context.set_deadline(std::chrono::system_clock::now() + 60s);
  auto reader = stub->Generate(&context, endless);
  v1::MeshEvent event;
  // Its first progress: the job is in its iterations.
  while (reader->Read(&event) && !event.has_progress()) {
  }
  ASSERT_TRUE(event.has_progress());
  v1::JobRef ref;
  ref.set_job_id(event.job_id());
  v1::JobInfo info;
  auto cancel_context = context_with_deadline();
  ASSERT_TRUE(stub->Cancel(cancel_context.get(), ref, &info).ok());
  while (reader->Read(&event)) {
  }
  EXPECT_EQ(reader->Finish().error_code(), grpc::StatusCode::CANCELLED);
  EXPECT_TRUE(eventually([&] { return server.server().jobs().live_jobs() == 0; }));
}

}  // namespace
}  // namespace meshd::testing
