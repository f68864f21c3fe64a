// What scripts/fuzz.sh found (tests/fuzz/FINDINGS.md), as plain tests of the normal build: each
// finding's request and the outcome its fix gives, and every input of tests/fuzz/corpus/ replayed
// through the fuzzer's own pipeline (tests/fuzz/request_pipeline.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "client/request_file.h"
#include "core/common/error.h"
#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh3d/generate_mesh3d.h"
#include "core/mesh/validity.h"
#include "core/mesh3d/tet_validity.h"
#include "server/request_conversion.h"
#include "tests/fuzz/request_pipeline.h"

namespace meshd {
namespace {

v1::MeshRequest parse(const std::string& text) { return parse_request_text(text, "test"); }

// The bytes of a file, as the fuzzer reads an input.
std::string file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Converts `text` under `limits` and returns the error it throws; fails the test when none.
Error refusal(const std::string& text, const ConversionLimits& limits = {}) {
  try {
    to_job_spec(parse(text), limits);
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "accepted: " << text;
  return Error(ErrorCode::kInternal, "", "accepted");
}

// ---------------------------------------------------------------------------------------------
// The corpus: every input runs through the pipeline without anything but a meshd::Error.

TEST(FuzzRegression, CorpusReplaysCleanly) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(MESHD_FUZZ_CORPUS)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_FALSE(files.empty()) << MESHD_FUZZ_CORPUS;
  for (const auto& file : files) {
    SCOPED_TRACE(file.filename().string());
    const std::string bytes = file_bytes(file);
    EXPECT_NO_THROW(
        fuzz::run_request_input(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()));
  }
}

// ---------------------------------------------------------------------------------------------
// One test per finding.

// estimate-wide-rectangle: a 2.8e14 x 2 box gave the node estimate 4.7e9 columns of samples, an
// int overflow (UB) and, had it fitted, hours of sampling. The sample counts are now clamped per
// side, and the request is refused for what it is: far too many nodes.
TEST(FuzzRegression, WideRectangleEstimate) {
  const std::string text =
      "geometry { difference { base { rectangle { min { x: -281474976710656.06 y: -1 } "
      "max { x: 1 y: 1 } } } subtract { circle { radius: 0.5 } } } } h0: 0.04";
  const Error e = refusal(text);
  EXPECT_EQ(e.code(), ErrorCode::kResourceExhausted) << e.what();
  EXPECT_EQ(e.field(), "h0");
  EXPECT_NE(e.detail().find("more than the limit of 5000000"), std::string::npos) << e.what();
  // Thin the other way, and thin enough to need one row of samples: the estimate still measures
  // the area (1e-6 here), so the request is refused for too few nodes, not as empty.
  const Error thin =
      refusal("geometry { rectangle { min { x: 0 y: 0 } max { x: 1 y: 1e-6 } } } h0: 0.1");
  EXPECT_EQ(thin.field(), "h0");
  EXPECT_NE(thin.detail().find("at least 3 are needed"), std::string::npos) << thin.what();
}

// domain-name: a shape named "domain" gave a boundary group of that name, which the output
// files reserve for the domain's own group (check_validity: "boundary group names are empty,
// repeated or \"domain\""). Found by a probe input through the fuzz target's invariant check.
TEST(FuzzRegression, DomainIsAReservedName) {
  const Error e = refusal("geometry { name: \"domain\" circle { radius: 1 } } h0: 0.1");
  EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument) << e.what();
  EXPECT_EQ(e.field(), "geometry.name");
  EXPECT_NE(e.detail().find("\"domain\" is reserved for the domain's own group"), std::string::npos)
      << e.what();
  const Error nested = refusal(
      "geometry { difference { base { circle { radius: 1 } } subtract { name: \"domain\" "
      "circle { radius: 0.5 } } } } h0: 0.1");
  EXPECT_EQ(nested.field(), "geometry.difference.subtract[0].name");
  // Only the exact name: the file formats compare names exactly.
  EXPECT_NO_THROW(to_job_spec(parse("geometry { name: \"Domain\" circle { radius: 1 } } h0: 0.1")));
}

// thin-strip: a 1e4 x 1e-4 strip at h0 0.02 is about 2,900 nodes by its area, but every grid
// point of the row on its boundary is kept: 160,000 initial points under the fuzz limits, 7 s a
// run. The initial grid is now limited to 64 points per node of the limit.
TEST(FuzzRegression, ThinStripGrid) {
  const Error e = refusal("geometry { rectangle { max { x: 10000 y: 0.0001 } } } h0: 0.02",
                          fuzz::fuzz_limits());
  EXPECT_EQ(e.code(), ErrorCode::kResourceExhausted) << e.what();
  EXPECT_EQ(e.field(), "h0");
  EXPECT_NE(e.detail().find("the domain fills little of its box"), std::string::npos) << e.what();
}

// scale-overflow: two nested scales by 1e300 gave the circle an infinite radius (its center
// inf * 0 = nan); with a bbox it meshed to nothing, without one it was "unbounded". compile now
// checks every folded parameter.
TEST(FuzzRegression, ScaleOverflow) {
  const Error e = refusal(
      "geometry { scale { factor: 1e300 shape { scale { factor: 1e300 shape { circle { radius: 1 "
      "} } } } } } h0: 0.1 bbox { min { x: -1 y: -1 } max { x: 1 y: 1 } }");
  EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument) << e.what();
  EXPECT_EQ(e.field(), "geometry.scale.shape.scale.shape");
  EXPECT_NE(e.detail().find("within +-1e150"), std::string::npos) << e.what();
}

// radius-1e200: squares of coordinates beyond 1e154 overflow, so that every distance read inf and
// the disk was refused as "empty". Such coordinates are now refused as out of range.
TEST(FuzzRegression, CoordinatesBeyond1e150) {
  const Error e = refusal("geometry { circle { radius: 1e200 } } h0: 1e199");
  EXPECT_EQ(e.field(), "geometry");
  EXPECT_NE(e.detail().find("is 1e+200"), std::string::npos) << e.what();
}

// far-from-origin: a unit disk at x = 1e15 meshed at h0 = 0.1 (doubles there are 0.125 apart)
// gave a "valid" mesh of slivers, q_min 0.000; at 2e7 it lost all but 11 of 300 nodes. Refused
// now when the box reaches beyond 1e7 finest edges from the origin.
TEST(FuzzRegression, FarFromTheOrigin) {
  const Error e = refusal("geometry { circle { center { x: 1e15 } radius: 1 } } h0: 0.1");
  EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument) << e.what();
  EXPECT_EQ(e.field(), "h0");
  EXPECT_NE(e.detail().find("move the geometry towards the origin"), std::string::npos) << e.what();
}

// ---------------------------------------------------------------------------------------------
// Open findings: faults in core/distmesh, reported, each with the outcome its fix should give.
// Disabled until then; the fuzz pipeline skips over them meanwhile (request_pipeline.cpp).

struct Meshed {
  JobSpec spec;
  MeshResult result;
};

Meshed mesh(const std::string& text) {
  Meshed m{to_job_spec(parse(text)), {}};
  ThreadPool pool(1);
  CpuEngine engine(pool);
  m.result = generate_mesh(m.spec.plane, engine, nullptr, nullptr);
  return m;
}

// thinner-than-an-edge: a 4 x 1.2e-4 ellipse at h0 = 1.2e-3, a tenth of an edge thick, was
// estimated at 300 nodes by its area and meshed to none, "converged". A domain that is nowhere
// a quarter of its finest edge deep is now refused, with the h0 at which it meshes.
TEST(FuzzRegression, ThinnerThanAnEdge) {
  const std::string ellipse =
      "geometry { ellipse { semi_axis_x: 2.0068359375000466 semi_axis_y: 6.0193240670969317e-05 "
      "} } h0: ";
  const Error e = refusal(ellipse + "0.0012036132813494759");
  EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument) << e.what();
  EXPECT_EQ(e.field(), "h0");
  EXPECT_NE(e.detail().find("no triangle of that size fits; h0 must be at most about 0.0002"),
            std::string::npos)
      << e.what();
  // At the h0 it names the ellipse is half an edge across: one row of elements along it (the
  // area estimate counts twice as many nodes as such a row has).
  const Meshed m = mesh(ellipse + "0.0002");
  EXPECT_GT(static_cast<double>(m.result.mesh.triangles.size()), 0.25 * m.spec.estimated_nodes);
  EXPECT_TRUE(check_validity(m.result.mesh).valid());
}

// denormal-circle: a circle of radius 5e-324 made the node estimate's cell size underflow to
// 0, so that it took 1e4 x 1e4 coarse cells: 1.8 GB for one request. Now the estimate's cells
// stay within its budget and the request is refused as empty.
TEST(FuzzRegression, DenormalCircle) {
  const Error e =
      refusal("geometry { circle { radius: 4.94065645841247e-324 } } h0: 0.54622091293334962");
  EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument) << e.what();
  EXPECT_EQ(e.field(), "geometry");
  EXPECT_NE(e.detail().find("the domain is empty"), std::string::npos) << e.what();
}

// fscale-2: density control removes the points whose bars are shorter than half their target
// L0 = fscale * scaled size, so that from fscale ~1.35 on it removes most of them every time:
// G1 (2,300 nodes) ends with 4 nodes at fscale 1.5 and none at 2, "converged". 1.3 no longer
// converges. The proto allows [1, 2].
TEST(FuzzRegression, DISABLED_FscaleAtTheTopOfItsRangeKeepsTheMesh) {
  for (const char* fscale : {"1.5", "2"}) {
    const Meshed m = mesh(std::string("geometry { circle { radius: 1 } } h0: 0.05 params { "
                                      "fscale: ") +
                          fscale + " }");
    EXPECT_GT(static_cast<double>(m.result.mesh.points.size()), 0.5 * m.spec.estimated_nodes)
        << "fscale " << fscale;
  }
}

// cleanup-empties-thin-ellipse and ellipse-one-row: an ellipse two edges across (4.1 x 0.125 or
// 1.0 x 0.125 at h0 0.06) is 2.4 grid rows high. The grid spanned the box exactly, so two of its
// three rows lay on the boundary and only the middle one stayed: collinear points. The long
// ellipse relaxed to 62 nodes and the clean-up then removed them all; the short one had no
// triangle from the start, "converged" with no node. Such boxes now get their rows centred.
//
// density-empties-thin-ellipse: the long one with semi_axis_y 0.0625002284185791 (1e-8 less)
// kept its rows, yet density control removed 97 of 142 nodes at once (the strip's long sliver
// bars inflated the L0 scale) and the clean-up the rest. A removal of more than a quarter of the
// free nodes at once is now skipped (distmesh.cpp).
TEST(FuzzRegression, EllipseTwoEdgesAcrossMeshes) {
  for (const char* semi_axes :
       {"semi_axis_x: 2.0539119349977444 semi_axis_y: 0.0625002384185791",
        "semi_axis_x: 0.50539114988722 semi_axis_y: 0.0625002384185791",
        "semi_axis_x: 2.0539119349977444 semi_axis_y: 0.0625002284185791"}) {
    const Meshed m = mesh(std::string("geometry { ellipse { ") + semi_axes + " } } h0: 0.06");
    SCOPED_TRACE(semi_axes);
    EXPECT_GT(static_cast<double>(m.result.mesh.points.size()), 0.5 * m.spec.estimated_nodes);
    EXPECT_GT(m.result.mesh.triangles.size(), m.result.mesh.points.size() / 2);
    EXPECT_TRUE(check_validity(m.result.mesh).valid());
  }
}

// torus-density-empties: the torus at h0 0.16, its tube about four edges across, with density
// control at every step: the first check found all 326 nodes crowded and the mesh emptied. The
// volume loop now skips a removal of more than a quarter of the free nodes, as the plane loop
// does. gem-edge-needle (the faceted gem at h0 0.84) kept a tetrahedron of four samples along one
// straight edge, flat by the validity check's rule but not by a radius ratio; the engine now
// drops what the check refuses.
TEST(FuzzRegression, CoarseVolumesKeepTheirNodesAndAValidMesh) {
  for (const char* name : {"torus-density-empties", "gem-edge-needle"}) {
    const std::string input = file_bytes(std::filesystem::path(MESHD_FUZZ_CORPUS) / name);
    ASSERT_GT(input.size(), 1u) << name;
    SCOPED_TRACE(name);
    JobSpec spec = to_job_spec(parse(input.substr(1)));  // the first byte picks the format
    ASSERT_TRUE(spec.volume);
    spec.volume->params.max_iterations = 50;  // as the harness meshed them
    const MeshResult3 result = generate_mesh3d(*spec.volume, nullptr, nullptr, nullptr);
    EXPECT_GT(static_cast<double>(result.mesh.points.size()), 0.5 * spec.estimated_nodes);
    const TetValidityReport report = check_tet_validity(result.mesh);
    EXPECT_TRUE(report.valid()) << (report.valid() ? "" : report.problems.front());
  }
}

// size-floor-not-reached: compile_problem folds the size field's lower bound into h0, and the
// initial points keep a grid point with probability (smallest sampled h / h)^2. Where the domain
// never reaches the bound (h_min 1 only within 1e-20 of a tiny circle, h_max 4 elsewhere) every
// grid point is kept: 16 times the estimated nodes (bounded now by the grid limit of
// to_job_spec, 64 points per node of the node limit).
TEST(FuzzRegression, DISABLED_SizeFloorNotReachedKeepsTheEstimate) {
  const Meshed m = mesh(
      "geometry { rectangle { min { x: -1 y: -1 } max { x: 1 y: 1 } } } h0: 0.01 size { terms { "
      "distance { shape { circle { center { x: 0.5 } radius: 0.001 } } h_min: 1 slope: 1e20 "
      "h_max: 4 } } }");
  EXPECT_LT(static_cast<double>(m.result.mesh.points.size()), 2 * m.spec.estimated_nodes);
}

}  // namespace
}  // namespace meshd
