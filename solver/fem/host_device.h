// What makes a function of the kernels compile for the CPU and (under nvcc) the GPU alike.
#pragma once

#if defined(__CUDACC__)
#define GALSCULPT_HD __host__ __device__ inline
#else
#define GALSCULPT_HD inline
#endif
// Unrolls the loop that follows where the compiler takes GCC's pragma (not under nvcc).
#if defined(__GNUC__) && !defined(__clang__) && !defined(__CUDACC__)
#define GALSCULPT_UNROLL _Pragma("GCC unroll 8")
#else
#define GALSCULPT_UNROLL
#endif
