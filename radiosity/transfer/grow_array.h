// A growable array of trivially copyable values whose storage grows with realloc.
//
// The solver keeps several values per element and per receiver, and these arrays grow
// by the tens of megabytes while a solve refines. std::vector grows by allocating
// anew and copying, which for blocks this large means fresh pages (a page fault per
// 4 KiB) and a copy, on the thread that refines, while the other threads wait. glibc
// grows a large block with mremap instead: the pages move, nothing is copied or
// faulted again. (Written here because no library of the project's stack offers
// realloc growth: Boost.Container and oneTBB allocate and copy as std::vector does.)
#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>
#include <type_traits>
#include <utility>

namespace dynrad::rad {

template <class T>
class GrowArray {
  static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>,
                "GrowArray moves its values with realloc");

 public:
  GrowArray() = default;
  GrowArray(const GrowArray&) = delete;
  GrowArray& operator=(const GrowArray&) = delete;
  GrowArray(GrowArray&& o) noexcept { swap(o); }
  GrowArray& operator=(GrowArray&& o) noexcept {
    swap(o);
    return *this;
  }
  ~GrowArray() { std::free(data_); }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  T* begin() { return data_; }
  T* end() { return data_ + size_; }
  const T* begin() const { return data_; }
  const T* end() const { return data_ + size_; }

  // New values (from the old size on) are `fill`; shrinking keeps the storage.
  void resize(std::size_t count, const T& fill = T{}) {
    if (count > capacity_) grow(count);
    for (std::size_t i = size_; i < count; ++i) data_[i] = fill;
    size_ = count;
  }
  // New values are left unset, for the caller to write (in parallel, say) before any read.
  void resize_for_overwrite(std::size_t count) {
    if (count > capacity_) grow(count);
    size_ = count;
  }
  void assign(std::size_t count, const T& fill) {
    size_ = 0;
    resize(count, fill);
  }

 private:
  void grow(std::size_t count) {
    std::size_t capacity = capacity_ + capacity_ / 2;  // 1.5x: mremap makes growth cheap anyway
    if (capacity < count) capacity = count;
    if (capacity > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_alloc();
    void* p = std::realloc(static_cast<void*>(data_), capacity * sizeof(T));
    if (!p) throw std::bad_alloc();
    data_ = static_cast<T*>(p);
    capacity_ = capacity;
  }
  void swap(GrowArray& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(capacity_, o.capacity_);
  }

  T* data_ = nullptr;
  std::size_t size_ = 0, capacity_ = 0;
};

}  // namespace dynrad::rad
