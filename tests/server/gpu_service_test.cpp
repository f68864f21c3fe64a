// The service on a GPU: a GPU worker per visible device, BACKEND_AUTO and BACKEND_GPU run there,
// BACKEND_CPU on the CPU worker beside it, and the device memory metric is set. Skips where no
// GPU is visible (CI).
#include <gtest/gtest.h>

#include "server/worker_engine.h"
#include "tests/server/test_server.h"

namespace meshd::testing {
namespace {

class GpuService : public ::testing::Test {
 protected:
  void SetUp() override {
    if (usable_gpu_count() == 0) GTEST_SKIP() << "no GPU visible (or no GPU engine in this build)";
  }
};

TEST_F(GpuService, JobsRunOnTheBackendTheyAskFor) {
  ServerOptions options = test_options();
  options.backend = Backend::kAuto;
  TestServer server(options, workers_for(options));
  auto stub = server.stub();
  for (const auto backend :
       {v1::JobOptions::BACKEND_AUTO, v1::JobOptions::BACKEND_GPU, v1::JobOptions::BACKEND_CPU}) {
    SCOPED_TRACE(v1::JobOptions::Backend_Name(backend));
    const StreamResult r = generate(*stub, disk_request(0.02, backend));
    ASSERT_TRUE(r.status.ok()) << r.status.error_message();
    EXPECT_TRUE(r.checksum_ok);
    EXPECT_GE(r.done.quality().q_min(), 0.6);
    EXPECT_NEAR(static_cast<double>(r.done.nodes()), 3.63 / (0.02 * 0.02), 0.05 * 9000);
    const auto expected = backend == v1::JobOptions::BACKEND_CPU ? v1::JobOptions::BACKEND_CPU
                                                                 : v1::JobOptions::BACKEND_GPU;
    EXPECT_EQ(r.done.backend(), expected);
    if (expected == v1::JobOptions::BACKEND_GPU) {
      EXPECT_NE(r.done.device().find("(device 0)"), std::string::npos) << r.done.device();
    }
  }
  const std::string metrics = server.server().metrics().text();
  EXPECT_NE(metrics.find("meshd_device_memory_bytes{device=\"0\"}"), std::string::npos);
}

// A volume asked for the GPU runs its steps on the GPU worker's 3D engine; BACKEND_AUTO sends it
// to the CPU worker beside it.
TEST_F(GpuService, VolumesRunOnTheGpuWhenAsked) {
  ServerOptions options = test_options();
  options.backend = Backend::kAuto;
  TestServer server(options, workers_for(options));
  auto stub = server.stub();
  for (const auto backend : {v1::JobOptions::BACKEND_GPU, v1::JobOptions::BACKEND_AUTO}) {
    SCOPED_TRACE(v1::JobOptions::Backend_Name(backend));
    v1::MeshRequest request;
    request.mutable_volume()->mutable_geometry()->mutable_sphere()->set_radius(1.0);
    request.set_h0(0.15);
    request.mutable_options()->set_backend(backend);
    const StreamResult r = generate(*stub, request);
    ASSERT_TRUE(r.status.ok()) << r.status.error_message();
    EXPECT_TRUE(r.checksum_ok);
    EXPECT_EQ(r.done.backend(), backend == v1::JobOptions::BACKEND_GPU
                                    ? v1::JobOptions::BACKEND_GPU
                                    : v1::JobOptions::BACKEND_CPU);
    EXPECT_GT(r.done.quality().q_min(), 0.2);
    EXPECT_GT(r.done.quality().min_dihedral_deg(), 10.0);
    EXPECT_LT(r.done.quality().max_surface_offset(), 1e-3 * 0.15);
  }
}

// A job larger than the largest before grows the worker's arena; the same size again reuses it.
TEST_F(GpuService, GpuWorkerKeepsItsEngineWarmAcrossJobs) {
  ServerOptions options = test_options();
  options.backend = Backend::kGpu;
  TestServer server(options, workers_for(options));
  auto stub = server.stub();
  const StreamResult first = generate(*stub, disk_request(0.005, v1::JobOptions::BACKEND_GPU));
  ASSERT_TRUE(first.status.ok()) << first.status.error_message();
  const StreamResult second = generate(*stub, disk_request(0.005, v1::JobOptions::BACKEND_GPU));
  ASSERT_TRUE(second.status.ok());
  EXPECT_EQ(first.done.nodes(), second.done.nodes());  // same bits on a warm engine
  EXPECT_EQ(first.done.result_sha256(), second.done.result_sha256());
}

// A GPU worker's warm-up leaves its arena large enough for a small job: the first ~2k-node job
// after the start allocates no device memory.
TEST_F(GpuService, AWarmWorkersFirstSmallJobAllocatesNothing) {
  ServerOptions options = test_options();
  options.backend = Backend::kGpu;
  TestServer server(options, workers_for(options));
  auto stub = server.stub();
  const int64_t before = gpu_allocation_count();
  const StreamResult r = generate(*stub, disk_request(0.04, v1::JobOptions::BACKEND_GPU));
  ASSERT_TRUE(r.status.ok()) << r.status.error_message();
  EXPECT_GT(r.done.nodes(), 2000);
  EXPECT_EQ(gpu_allocation_count(), before);
}

// Many workers share a device: no kernel loads lazily under load (it would wait until the whole
// device is idle), and threads waiting for their streams yield their cores. SetUp's
// usable_gpu_count is this process's first CUDA call.
TEST_F(GpuService, WorkersLoadEveryKernelAtTheStartAndYieldWhileTheyWait) {
  for (int device = 0; device < usable_gpu_count(); ++device) {
    EXPECT_TRUE(gpus_shared_among_workers(device)) << "device " << device;
  }
}

}  // namespace
}  // namespace meshd::testing
