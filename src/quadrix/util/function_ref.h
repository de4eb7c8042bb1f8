// FunctionRef<R(Args...)>: a non-owning reference to a callable, for a parameter that is only
// called while the call that receives it runs. What std::function is there, without the copy of
// the callable (and, for a capture larger than two pointers, a heap allocation and a free) each
// time one is made: the shader makes one per pixel (its shadow test), about a million a picture.
//
// The callable must outlive every call through the reference: pass one down, never keep one
// beyond the callee's return. It refers to callable objects (lambdas, functors), not to plain
// functions. A default-constructed FunctionRef is empty (false); calling it is undefined.
#pragma once

#include <functional>
#include <memory>
#include <type_traits>
#include <utility>

namespace quadrix {

template <class Signature>
class FunctionRef;

template <class R, class... Args>
class FunctionRef<R(Args...)> {
    // A callable object (not a plain function, not another FunctionRef) callable as R(Args...).
    template <class F>
    static constexpr bool kReferable =
        !std::is_same_v<std::remove_cvref_t<F>, FunctionRef> &&
        !std::is_function_v<std::remove_reference_t<F>> && std::is_invocable_r_v<R, F&, Args...>;

  public:
    FunctionRef() = default;

    template <class F, std::enable_if_t<kReferable<F>, int> = 0>
    FunctionRef(F&& f) noexcept  // NOLINT(google-explicit-constructor): as std::function
        : object_(const_cast<void*>(static_cast<const void*>(std::addressof(f)))),
          call_([](void* object, Args... args) -> R {
              return std::invoke(*static_cast<std::remove_reference_t<F>*>(object),
                                 std::forward<Args>(args)...);
          }) {}

    explicit operator bool() const { return call_ != nullptr; }

    R operator()(Args... args) const { return call_(object_, std::forward<Args>(args)...); }

  private:
    void* object_ = nullptr;
    R (*call_)(void*, Args...) = nullptr;
};

}  // namespace quadrix
