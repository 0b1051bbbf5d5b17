#pragma once
// Owns a polymorphic T that is copied through T::clone() and assigned through T::assign(const
// T&) (which must not allocate): a class holding one keeps its defaulted copy constructor, so a
// control snapshot (stepper.hpp) is a plain copy. Private to solvers.
#include <memory>
#include <utility>

namespace rodlab::solvers {

template <class T>
class Cloned {
 public:
  explicit Cloned(std::unique_ptr<T> p) : p_(std::move(p)) {}
  Cloned(const Cloned& other) : p_(other.p_->clone()) {}
  Cloned& operator=(const Cloned& other) {
    p_->assign(*other.p_);
    return *this;
  }
  Cloned(Cloned&&) noexcept = default;
  Cloned& operator=(Cloned&&) noexcept = default;
  ~Cloned() = default;

  T* operator->() const { return p_.get(); }
  T& operator*() const { return *p_; }

 private:
  std::unique_ptr<T> p_;
};

}  // namespace rodlab::solvers
