// cuSOLVER's dense Cholesky, loaded when first asked for (dlopen) instead of linked: linking
// libcusolver pulls cuBLAS, cuBLASLt and cuSPARSE into every process at start-up (about 250 MB
// resident before main, on machines with no GPU too), while only a scene asking for a dense
// coarse Cholesky on the GPU needs it. Without the library, factor() says so and the device
// multigrid uses its coarse CG, as the CPU does when a factorization fails.
#pragma once

#include <cusolverDn.h>
#include <dlfcn.h>

#include <string>

namespace galsculpt::gpu {

class CusolverLibrary {
 public:
  CusolverLibrary() = default;
  CusolverLibrary(const CusolverLibrary&) = delete;
  CusolverLibrary& operator=(const CusolverLibrary&) = delete;
  ~CusolverLibrary() {
    if (handle_) destroy_(handle_);
    if (library_) dlclose(library_);
  }

  // Loads the library and makes a handle on `stream` (once); false, with the reason, if not.
  bool load(cudaStream_t stream, std::string& reason) {
    if (handle_) return true;
    if (!reason_.empty()) {
      reason = reason_;
      return false;
    }
    for (const char* name : {"libcusolver.so.12", "libcusolver.so.11", "libcusolver.so"}) {
      library_ = dlopen(name, RTLD_NOW | RTLD_LOCAL);
      if (library_) break;
    }
    if (!library_) return fail("cannot load libcusolver (" + std::string(dlerror()) + ")", reason);
    if (!symbol(create_, "cusolverDnCreate") || !symbol(destroy_, "cusolverDnDestroy") ||
        !symbol(setStream_, "cusolverDnSetStream") ||
        !symbol(bufferSize_, "cusolverDnDpotrf_bufferSize") ||
        !symbol(potrf_, "cusolverDnDpotrf") || !symbol(potrs_, "cusolverDnDpotrs"))
      return fail("libcusolver lacks the dense Cholesky entry points", reason);
    cusolverDnHandle_t h = nullptr;
    if (create_(&h) != CUSOLVER_STATUS_SUCCESS || setStream_(h, stream) != CUSOLVER_STATUS_SUCCESS)
      return fail("cuSOLVER could not start", reason);
    handle_ = h;
    return true;
  }

  cusolverStatus_t bufferSize(int n, double* a, int* lwork) const {
    return bufferSize_(handle_, CUBLAS_FILL_MODE_LOWER, n, a, n, lwork);
  }
  cusolverStatus_t potrf(int n, double* a, double* work, int lwork, int* info) const {
    return potrf_(handle_, CUBLAS_FILL_MODE_LOWER, n, a, n, work, lwork, info);
  }
  // b (n x columns, column-major) = (L Lᵀ)⁻¹ b.
  cusolverStatus_t potrs(int n, int columns, const double* l, double* b, int* info) const {
    return potrs_(handle_, CUBLAS_FILL_MODE_LOWER, n, columns, l, n, b, n, info);
  }

 private:
  template <typename F>
  bool symbol(F& f, const char* name) {
    f = reinterpret_cast<F>(dlsym(library_, name));
    return f != nullptr;
  }
  bool fail(const std::string& why, std::string& reason) {
    reason_ = reason = why;
    return false;
  }

  void* library_ = nullptr;
  cusolverDnHandle_t handle_ = nullptr;
  std::string reason_;
  cusolverStatus_t (*create_)(cusolverDnHandle_t*) = nullptr;
  cusolverStatus_t (*destroy_)(cusolverDnHandle_t) = nullptr;
  cusolverStatus_t (*setStream_)(cusolverDnHandle_t, cudaStream_t) = nullptr;
  cusolverStatus_t (*bufferSize_)(cusolverDnHandle_t, cublasFillMode_t, int, double*, int,
                                  int*) = nullptr;
  cusolverStatus_t (*potrf_)(cusolverDnHandle_t, cublasFillMode_t, int, double*, int, double*, int,
                             int*) = nullptr;
  cusolverStatus_t (*potrs_)(cusolverDnHandle_t, cublasFillMode_t, int, int, const double*, int,
                             double*, int, int*) = nullptr;
};

}  // namespace galsculpt::gpu
