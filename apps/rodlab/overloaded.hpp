#pragma once
// std::visit helper: Overloaded{[](const A&) {...}, [](const B&) {...}}.

namespace rodlab::cli {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace rodlab::cli
