/// \file sundials_compat.hpp
/// \brief The one place that knows which SUNDIALS release the solver is built against:
/// 6.x (Debian 12) or 7.x (Debian 13). Private to the solver (integrators.cpp).
///
/// What differs, and what this header gives for it:
/// - the real type (`realtype`, gone in 7.0: `sunrealtype`) → `sun::Real`;
/// - the context's communicator (7.0 built with MPI needs `SUN_COMM_NULL`, not a null
///   pointer, or it aborts) → `sun::create_context`;
/// - error handlers (the per-integrator `*SetErrHandlerFn` are gone in 7.0; handlers hang on
///   the context) → `sun::route_context_errors` and `sun::route_integrator_errors`;
/// - ARKODE's stepper functions (`ERKStep*` setters and getters are deprecated in 7.1 in
///   favour of the shared `ARKode*` ones) → the `sun::erk` table of named functions.
/// Nothing else in the tree tests SUNDIALS_VERSION_*.
#pragma once

#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <sundials/sundials_config.h>
#include <sundials/sundials_context.h>

#include <string>

#define PCRF_SUNDIALS_AT_LEAST(major, minor) \
  (SUNDIALS_VERSION_MAJOR > (major) || (SUNDIALS_VERSION_MAJOR == (major) && SUNDIALS_VERSION_MINOR >= (minor)))

namespace pcrf::detail::sun {

#if PCRF_SUNDIALS_AT_LEAST(7, 0)
using Real = sunrealtype;
#else
using Real = realtype;
#endif

/// A SUNDIALS function and its name, for the message of a failing call.
template <class F>
struct Named {
  F* fn;
  const char* name;
};
#define PCRF_SUNDIALS_NAMED(fn) ::pcrf::detail::sun::Named<decltype(fn)>{fn, #fn}

/// SUNContext_Create for a serial context. Returns its flag (0: success).
inline int create_context(SUNContext* context) {
#if PCRF_SUNDIALS_AT_LEAST(7, 0)
  return SUNContext_Create(SUN_COMM_NULL, context);
#else
  return SUNContext_Create(nullptr, context);
#endif
}

/// Where SUNDIALS reports a failure instead of printing it: a study of thousands of cases
/// must not flood the terminal, and the text belongs in the case's message.
struct ErrorSink {
  const char* package;  ///< "CVODE" or "ARKODE", the start of the message
  std::string text;     ///< "PACKAGE::function (flag n): what SUNDIALS said"; empty: none yet
};

namespace internal {
inline void record(ErrorSink& sink, int flag, const char* function, const char* message) {
  sink.text = std::string(sink.package) + "::" + function + " (flag " + std::to_string(flag) + "): " + message;
}
#if PCRF_SUNDIALS_AT_LEAST(7, 0)
inline void on_error(int /*line*/, const char* function, const char* /*file*/, const char* message, SUNErrCode code,
                     void* sink, SUNContext /*context*/) {
  record(*static_cast<ErrorSink*>(sink), code, function, message != nullptr ? message : SUNGetErrMsg(code));
}
#else
inline void on_error(int code, const char* /*module*/, const char* function, char* message, void* sink) {
  record(*static_cast<ErrorSink*>(sink), code, function, message);
}
#endif
}  // namespace internal

/// Sends the errors reported through `context` to `sink` only (SUNDIALS 7 keeps error
/// handlers on the context and calls every one of its stack: the default one, which
/// prints, is removed first). SUNDIALS 6: nothing to do here (see route_integrator_errors).
/// `check(flag, name)` checks each call.
template <class Check>
void route_context_errors(SUNContext context, ErrorSink& sink, Check check) {
#if PCRF_SUNDIALS_AT_LEAST(7, 0)
  check(SUNContext_ClearErrHandlers(context), "SUNContext_ClearErrHandlers");
  check(SUNContext_PushErrHandler(context, internal::on_error, &sink), "SUNContext_PushErrHandler");
#else
  (void)context, (void)sink, (void)check;
#endif
}

enum class Package { kCvode, kArkodeErk };

/// Sends the errors of the integrator `memory` to `sink` only (SUNDIALS 6 keeps the handler
/// on the integrator). SUNDIALS 7: nothing to do here (see route_context_errors).
template <class Check>
void route_integrator_errors(void* memory, Package package, ErrorSink& sink, Check check) {
#if PCRF_SUNDIALS_AT_LEAST(7, 0)
  (void)memory, (void)package, (void)sink, (void)check;
#else
  if (package == Package::kCvode) {
    check(CVodeSetErrHandlerFn(memory, internal::on_error, &sink), "CVodeSetErrHandlerFn");
  } else {
    check(ERKStepSetErrHandlerFn(memory, internal::on_error, &sink), "ERKStepSetErrHandlerFn");
  }
#endif
}

/// ARKODE ERKStep's functions under their current names: the shared `ARKode*` ones from
/// 7.1 on, the stepper's own before (creation, re-initialization and the table choice stay
/// `ERKStep*`).
namespace erk {
#if PCRF_SUNDIALS_AT_LEAST(7, 1)
#define PCRF_ERK(name) PCRF_SUNDIALS_NAMED(ARKode##name)
#else
#define PCRF_ERK(name) PCRF_SUNDIALS_NAMED(ERKStep##name)
#endif
inline constexpr auto free_memory = PCRF_ERK(Free);
inline constexpr auto set_user_data = PCRF_ERK(SetUserData);
inline constexpr auto sv_tolerances = PCRF_ERK(SVtolerances);
inline constexpr auto set_max_num_steps = PCRF_ERK(SetMaxNumSteps);
inline constexpr auto set_max_err_test_fails = PCRF_ERK(SetMaxErrTestFails);
inline constexpr auto set_max_hnil_warns = PCRF_ERK(SetMaxHnilWarns);
inline constexpr auto set_max_step = PCRF_ERK(SetMaxStep);
inline constexpr auto root_init = PCRF_ERK(RootInit);
inline constexpr auto set_no_inactive_root_warn = PCRF_ERK(SetNoInactiveRootWarn);
inline constexpr auto set_init_step = PCRF_ERK(SetInitStep);
inline constexpr auto set_stop_time = PCRF_ERK(SetStopTime);
inline constexpr auto set_root_direction = PCRF_ERK(SetRootDirection);
inline constexpr auto evolve = PCRF_ERK(Evolve);
inline constexpr auto get_root_info = PCRF_ERK(GetRootInfo);
inline constexpr auto get_dky = PCRF_ERK(GetDky);
inline constexpr auto get_num_steps = PCRF_ERK(GetNumSteps);
inline constexpr auto get_num_g_evals = PCRF_ERK(GetNumGEvals);
#undef PCRF_ERK

/// Right-hand-side evaluations (7.2 moved the count to ARKODE, with a partition index).
#if PCRF_SUNDIALS_AT_LEAST(7, 2)
inline int count_rhs_evals(void* memory, long* count) { return ARKodeGetNumRhsEvals(memory, 0, count); }
inline constexpr Named<int(void*, long*)> get_num_rhs_evals{count_rhs_evals, "ARKodeGetNumRhsEvals"};
#else
inline constexpr auto get_num_rhs_evals = PCRF_SUNDIALS_NAMED(ERKStepGetNumRhsEvals);
#endif
}  // namespace erk

}  // namespace pcrf::detail::sun
