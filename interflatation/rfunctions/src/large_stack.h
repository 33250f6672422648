#pragma once
// Internal: runs a function on a thread of its own with a large stack. Reading a model recurses
// along its expressions (parse tree, evaluation, differentiation, compilation, destruction),
// up to limits::expression_depth levels: more than the 8 MB a main thread usually has,
// particularly in sanitizer builds. The stack is address space only until it is used.

#include <exception>
#include <optional>
#include <pthread.h>
#include <stdexcept>
#include <utility>

namespace interlin::rf::detail {

// Stack of the reading thread: about 6 KB per expression level in the sanitizer build.
inline constexpr std::size_t kModelStackBytes = std::size_t(256) << 20;

// fn() on a thread with `bytes` of stack; its result or its exception comes back here.
template <class F>
auto on_large_stack(F&& fn, std::size_t bytes = kModelStackBytes) {
  using R = decltype(fn());
  struct Job {
    F& fn;
    std::optional<R> result;
    std::exception_ptr error;
  } job{fn, std::nullopt, nullptr};
  const auto run = [](void* p) -> void* {
    Job& j = *static_cast<Job*>(p);
    try {
      j.result.emplace(j.fn());
    } catch (...) {
      j.error = std::current_exception();
    }
    return nullptr;
  };
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, bytes);
  pthread_t thread;
  const int rc = pthread_create(&thread, &attr, run, &job);
  pthread_attr_destroy(&attr);
  if (rc != 0) // no thread to be had: run here (the limits still bound the recursion)
    return fn();
  pthread_join(thread, nullptr);
  if (job.error)
    std::rethrow_exception(job.error);
  return std::move(*job.result);
}

} // namespace interlin::rf::detail
