#pragma once
// Private FFTW helpers shared by the library's transforms. FFTW's planner is not thread-safe (only
// fftw_execute is), so making and destroying plans takes the library's one planner lock; the
// transforms themselves run concurrently.

#include <fftw3.h>

#include <cstddef>
#include <memory>
#include <mutex>
#include <new>
#include <utility>

namespace chaos::detail {

std::mutex& fftw_planner_mutex();

struct FftwFree {
  void operator()(void* p) const noexcept { fftw_free(p); }
};
template <class T>
using FftwBuffer = std::unique_ptr<T[], FftwFree>;

template <class T>
FftwBuffer<T> fftw_buffer(std::size_t count) {
  auto* p = static_cast<T*>(fftw_malloc(sizeof(T) * count));
  if (p == nullptr) throw std::bad_alloc();
  return FftwBuffer<T>(p);
}

class Plan {
 public:
  Plan() = default;
  explicit Plan(fftw_plan p) : p_(p) {
    if (p_ == nullptr) throw std::bad_alloc();
  }
  ~Plan() { reset(); }
  Plan(Plan&& other) noexcept : p_(std::exchange(other.p_, nullptr)) {}
  Plan& operator=(Plan&& other) noexcept {
    if (this != &other) {
      reset();
      p_ = std::exchange(other.p_, nullptr);
    }
    return *this;
  }
  void execute() const noexcept { fftw_execute(p_); }

 private:
  void reset() noexcept {
    if (p_ == nullptr) return;
    std::lock_guard lock(fftw_planner_mutex());
    fftw_destroy_plan(p_);
    p_ = nullptr;
  }
  fftw_plan p_ = nullptr;
};

}  // namespace chaos::detail
