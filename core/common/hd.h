// Marks functions that run on both the host and the device. Code under core/ that the GPU
// engine shares lives in .cuh headers and uses MESHD_HD, so g++ and nvcc compile the same text.
#pragma once

#if defined(__CUDACC__)
#define MESHD_HD __host__ __device__
#else
#define MESHD_HD
#endif
