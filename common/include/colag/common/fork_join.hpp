#pragma once
// Fork-join parallelism offered to task code by the platform: a step that has a large, divisible
// piece of work (the UAV's scan insertion) splits it into parts that touch disjoint data and
// hands them to run(). Task code never owns threads; whether the parts run on several cores
// (platform::WorkerPool) or one after the other (SerialForkJoin) is the program's choice, and
// the result must not depend on it.
#include <type_traits>
#include <utility>

namespace colag {

// A non-owning reference to a callable: no allocation, trivially copyable. The callable must
// outlive the reference (pass temporaries only as call arguments).
template <class Signature>
class FunctionRef;

template <class R, class... Args>
class FunctionRef<R(Args...)> {
 public:
  template <class F>
  requires(!std::is_same_v<std::remove_cvref_t<F>, FunctionRef> &&
           std::is_invocable_r_v<R, F&, Args...>)
      // NOLINTNEXTLINE(google-explicit-constructor,bugprone-forwarding-reference-overload): used
      FunctionRef(F&& f)  // like a function parameter; the constraint keeps copies and moves
      : object_(const_cast<void*>(static_cast<const void*>(&f))),
        call_([](void* o, Args... args) -> R {
          return (*static_cast<std::remove_reference_t<F>*>(o))(std::forward<Args>(args)...);
        }) {}
  R operator()(Args... args) const { return call_(object_, std::forward<Args>(args)...); }

 private:
  void* object_;
  R (*call_)(void*, Args...);
};

class ForkJoin {
 public:
  virtual ~ForkJoin() = default;
  // How many parts can run at the same time (>= 1).
  virtual int concurrency() const = 0;
  // Runs part(0) .. part(parts - 1), possibly at the same time, and returns when all are done.
  // A part may call run() again (nested parts may then run on any thread).
  virtual void run(int parts, FunctionRef<void(int)> part) = 0;
};

class SerialForkJoin final : public ForkJoin {
 public:
  int concurrency() const override { return 1; }
  void run(int parts, FunctionRef<void(int)> part) override {
    for (int i = 0; i < parts; ++i)
      part(i);
  }
};

}  // namespace colag
