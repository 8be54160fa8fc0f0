// SUNDIALS adapters for the rocking ODE: CVODE (Adams / BDF) and ARKODE ERKStep.
//
// Every SUNDIALS call is checked through one helper (check_flag), which throws
// IntegratorError naming the call and the flag; every SUNDIALS object has one owner, so a
// throw frees what was made. Work counters are summed across re-initializations (SUNDIALS
// resets its own at each ReInit). What differs between SUNDIALS 6 and 7 is in
// sundials_compat.hpp.
#include "sundials_integrators.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <memory>
#include <string>
#include <type_traits>

#include "sundials_compat.hpp"

namespace pcrf::detail {
namespace {

using sun::Real;

/// The one check of every SUNDIALS call's flag: a negative flag is a failure.
void check_flag(int flag, const char* call) {
  if (flag < 0) throw IntegratorError(std::string(call) + " failed with flag " + std::to_string(flag));
}
template <class F, class... Args>
void call(sun::Named<F> f, Args... args) {
  check_flag(f.fn(args...), f.name);
}
/// The check of a constructor: NULL is a failure.
template <class T>
T check_ptr(T p, const char* call) {
  if (p == nullptr) throw IntegratorError(std::string(call) + " returned NULL");
  return p;
}

// ---- one owner per SUNDIALS object (destroyed before the context they were made in) ----
template <class Handle, void (*Free)(Handle)>
struct Freer {
  void operator()(Handle h) const { Free(h); }
};
template <class Handle, void (*Free)(Handle)>
using Owned = std::unique_ptr<std::remove_pointer_t<Handle>, Freer<Handle, Free>>;

void free_context(SUNContext c) { SUNContext_Free(&c); }
void free_linear_solver(SUNLinearSolver s) { SUNLinSolFree(s); }
void free_nonlinear_solver(SUNNonlinearSolver s) { SUNNonlinSolFree(s); }
void free_cvode(void* memory) { CVodeFree(&memory); }
void free_erk(void* memory) { sun::erk::free_memory.fn(&memory); }

using Context = Owned<SUNContext, free_context>;
using Vector = Owned<N_Vector, N_VDestroy>;
using Matrix = Owned<SUNMatrix, SUNMatDestroy>;
using LinearSolver = Owned<SUNLinearSolver, free_linear_solver>;
using NonlinearSolver = Owned<SUNNonlinearSolver, free_nonlinear_solver>;
using CvodeMemory = Owned<void*, free_cvode>;
using ErkMemory = Owned<void*, free_erk>;

Context make_context() {
  SUNContext c = nullptr;
  check_flag(sun::create_context(&c), "SUNContext_Create");
  return Context(check_ptr(c, "SUNContext_Create"));
}
Vector make_vector(SUNContext c) { return Vector(check_ptr(N_VNew_Serial(2, c), "N_VNew_Serial")); }

int rhs_thunk(Real t, N_Vector y, N_Vector ydot, void* user) {
  return static_cast<OdeProblem*>(user)->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
}
int root_thunk(Real t, N_Vector y, Real* g, void* user) {
  return static_cast<OdeProblem*>(user)->roots(t, N_VGetArrayPointer(y), g);
}
int jac_thunk(Real t, N_Vector y, N_Vector /*fy*/, SUNMatrix J, void* user, N_Vector, N_Vector, N_Vector) {
  double dfdy[4];
  const int flag = static_cast<OdeProblem*>(user)->jacobian(t, N_VGetArrayPointer(y), dfdy);
  SM_ELEMENT_D(J, 0, 0) = dfdy[0];
  SM_ELEMENT_D(J, 0, 1) = dfdy[1];
  SM_ELEMENT_D(J, 1, 0) = dfdy[2];
  SM_ELEMENT_D(J, 1, 1) = dfdy[3];
  return flag;
}

/// Owns the SUNDIALS context and the state vectors shared by both adapters.
class SundialsBase : public OdeIntegrator {
 protected:
  SundialsBase(const SolverSettings& s, OdeProblem& p, const char* package)
      : settings_(s), problem_(p), errors_{package, {}} {
    sun::route_context_errors(ctx_.get(), errors_, check_flag);
    N_VGetArrayPointer(atol_.get())[0] = s.atol_theta_rad;
    N_VGetArrayPointer(atol_.get())[1] = s.atol_omega_rad_s;
    N_VConst(0.0, y_.get());
  }
  void load(const double* y0) {
    N_VGetArrayPointer(y_.get())[0] = y0[0];
    N_VGetArrayPointer(y_.get())[1] = y0[1];
  }
  void store(double* y) const {
    y[0] = N_VGetArrayPointer(y_.get())[0];
    y[1] = N_VGetArrayPointer(y_.get())[1];
  }
  void store_dense(double* y) const {
    y[0] = N_VGetArrayPointer(dky_.get())[0];
    y[1] = N_VGetArrayPointer(dky_.get())[1];
  }
  const std::string& last_error() const override { return errors_.text; }

  /// Counters of the current segment (since the last ReInit).
  virtual SolverCounts segment() = 0;

  SolverCounts counts() override {
    SolverCounts c = done_;
    if (started_) add(c, segment());  // before the first start the counters are not set
    return c;
  }
  /// Banks the current segment's counters before a ReInit resets them.
  void accumulate() {
    if (started_) add(done_, segment());
  }
  /// SUNDIALS allocates its root counter without zeroing it and sets it during the first
  /// step's set-up; a segment whose set-up failed (no RHS evaluation at all) read it
  /// uninitialized. Such a segment evaluated nothing: its counts are zero.
  static SolverCounts settled(SolverCounts c) {
    if (c.rhs_evals == 0) c.root_evals = 0;
    return c;
  }
  static void add(SolverCounts& into, const SolverCounts& s) {
    into.steps += s.steps;
    into.rhs_evals += s.rhs_evals;
    into.root_evals += s.root_evals;
  }

  SolverSettings settings_;
  OdeProblem& problem_;
  // Declared first: destroyed last, after every object made in it.
  Context ctx_ = make_context();
  Vector y_ = make_vector(ctx_.get());
  Vector atol_ = make_vector(ctx_.get());
  Vector dky_ = make_vector(ctx_.get());  ///< dense output
  SolverCounts done_;  ///< counts of finished segments
  sun::ErrorSink errors_;
  bool started_ = false;
};

class CvodeIntegrator final : public SundialsBase {
 public:
  CvodeIntegrator(const SolverSettings& s, OdeProblem& p, bool bdf) : SundialsBase(s, p, "CVODE") {
    mem_.reset(check_ptr(CVodeCreate(bdf ? CV_BDF : CV_ADAMS, ctx_.get()), "CVodeCreate"));
    void* mem = mem_.get();
    sun::route_integrator_errors(mem, sun::Package::kCvode, errors_, check_flag);
    check_flag(CVodeInit(mem, rhs_thunk, 0.0, y_.get()), "CVodeInit");
    check_flag(CVodeSetUserData(mem, &problem_), "CVodeSetUserData");
    check_flag(CVodeSVtolerances(mem, s.rtol, atol_.get()), "CVodeSVtolerances");
    check_flag(CVodeSetMaxNumSteps(mem, s.max_steps), "CVodeSetMaxNumSteps");
    check_flag(CVodeSetMaxErrTestFails(mem, 50), "CVodeSetMaxErrTestFails");
    // No "t + h = t" warnings: SUNDIALS 7 prints them on stdout.
    check_flag(CVodeSetMaxHnilWarns(mem, -1), "CVodeSetMaxHnilWarns");
    if (s.max_step_s > 0) check_flag(CVodeSetMaxStep(mem, s.max_step_s), "CVodeSetMaxStep");
    check_flag(CVodeRootInit(mem, p.root_count(), root_thunk), "CVodeRootInit");
    check_flag(CVodeSetNoInactiveRootWarn(mem), "CVodeSetNoInactiveRootWarn");
    if (bdf) {
      A_.reset(check_ptr(SUNDenseMatrix(2, 2, ctx_.get()), "SUNDenseMatrix"));
      LS_.reset(check_ptr(SUNLinSol_Dense(y_.get(), A_.get(), ctx_.get()), "SUNLinSol_Dense"));
      check_flag(CVodeSetLinearSolver(mem, LS_.get(), A_.get()), "CVodeSetLinearSolver");
      if (p.has_jacobian()) check_flag(CVodeSetJacFn(mem, jac_thunk), "CVodeSetJacFn");
    } else {
      NLS_.reset(check_ptr(SUNNonlinSol_FixedPoint(y_.get(), 0, ctx_.get()), "SUNNonlinSol_FixedPoint"));
      check_flag(CVodeSetNonlinearSolver(mem, NLS_.get()), "CVodeSetNonlinearSolver");
    }
  }

  void restart(double t0, const double* y0, const int* root_dirs, double t_stop, double h0) override {
    accumulate();
    load(y0);
    check_flag(CVodeReInit(mem_.get(), t0, y_.get()), "CVodeReInit");
    check_flag(CVodeSetInitStep(mem_.get(), h0), "CVodeSetInitStep");
    check_flag(CVodeSetStopTime(mem_.get(), t_stop), "CVodeSetStopTime");
    check_flag(CVodeSetRootDirection(mem_.get(), const_cast<int*>(root_dirs)), "CVodeSetRootDirection");
    done_.reinits += started_ ? 1 : 0;
    started_ = true;
  }

  void set_stop_time(double t_stop) override {
    check_flag(CVodeSetStopTime(mem_.get(), t_stop), "CVodeSetStopTime");
  }

  Outcome advance(double tout, double& t, double* y, bool one_step) override {
    Real tret = t;
    // The flag is the outcome, not a set-up failure: a failure's text is in last_error().
    const int flag = CVode(mem_.get(), tout, y_.get(), &tret, one_step ? CV_ONE_STEP : CV_NORMAL);
    t = tret;
    store(y);
    if (flag == CV_ROOT_RETURN) return Outcome::kRoot;
    if (flag < 0) return Outcome::kFailure;
    return Outcome::kReachedTime;
  }

  void root_info(int* found) override { check_flag(CVodeGetRootInfo(mem_.get(), found), "CVodeGetRootInfo"); }

  void interpolate(double t, double* y) override {
    check_flag(CVodeGetDky(mem_.get(), t, 0, dky_.get()), "CVodeGetDky");
    store_dense(y);
  }

 private:
  SolverCounts segment() override {
    SolverCounts c;
    long nfe_ls = 0;
    check_flag(CVodeGetNumSteps(mem_.get(), &c.steps), "CVodeGetNumSteps");
    check_flag(CVodeGetNumRhsEvals(mem_.get(), &c.rhs_evals), "CVodeGetNumRhsEvals");
    if (LS_) check_flag(CVodeGetNumLinRhsEvals(mem_.get(), &nfe_ls), "CVodeGetNumLinRhsEvals");
    c.rhs_evals += nfe_ls;
    check_flag(CVodeGetNumGEvals(mem_.get(), &c.root_evals), "CVodeGetNumGEvals");
    return settled(c);
  }

  // Solvers before the memory that uses them: the memory is freed first.
  Matrix A_;
  LinearSolver LS_;
  NonlinearSolver NLS_;
  CvodeMemory mem_;
};

class ErkIntegrator final : public SundialsBase {
 public:
  ErkIntegrator(const SolverSettings& s, OdeProblem& p, ARKODE_ERKTableID table) : SundialsBase(s, p, "ARKODE") {
    mem_.reset(check_ptr(ERKStepCreate(rhs_thunk, 0.0, y_.get(), ctx_.get()), "ERKStepCreate"));
    void* mem = mem_.get();
    sun::route_integrator_errors(mem, sun::Package::kArkodeErk, errors_, check_flag);
    check_flag(ERKStepSetTableNum(mem, table), "ERKStepSetTableNum");
    call(sun::erk::set_user_data, mem, static_cast<void*>(&problem_));
    call(sun::erk::sv_tolerances, mem, s.rtol, atol_.get());
    call(sun::erk::set_max_num_steps, mem, s.max_steps);
    // A step across a record sample meets a kink in ü_g (linear interpolation): the
    // error test may fail many times before the step is small enough; the default of
    // 7 failures (each cutting h by at most 0.3) gives up too early for 8th order.
    call(sun::erk::set_max_err_test_fails, mem, 50);
    // No "t + h = t" warnings: SUNDIALS 7 prints them on stdout.
    call(sun::erk::set_max_hnil_warns, mem, -1);
    if (s.max_step_s > 0) call(sun::erk::set_max_step, mem, s.max_step_s);
    call(sun::erk::root_init, mem, p.root_count(), root_thunk);
    call(sun::erk::set_no_inactive_root_warn, mem);
  }

  void restart(double t0, const double* y0, const int* root_dirs, double t_stop, double h0) override {
    accumulate();
    load(y0);
    check_flag(ERKStepReInit(mem_.get(), rhs_thunk, t0, y_.get()), "ERKStepReInit");
    call(sun::erk::set_init_step, mem_.get(), h0);
    call(sun::erk::set_stop_time, mem_.get(), t_stop);
    call(sun::erk::set_root_direction, mem_.get(), const_cast<int*>(root_dirs));
    done_.reinits += started_ ? 1 : 0;
    started_ = true;
  }

  void set_stop_time(double t_stop) override { call(sun::erk::set_stop_time, mem_.get(), t_stop); }

  Outcome advance(double tout, double& t, double* y, bool one_step) override {
    Real tret = t;
    // The flag is the outcome, not a set-up failure: a failure's text is in last_error().
    const int flag = sun::erk::evolve.fn(mem_.get(), tout, y_.get(), &tret, one_step ? ARK_ONE_STEP : ARK_NORMAL);
    t = tret;
    store(y);
    if (flag == ARK_ROOT_RETURN) return Outcome::kRoot;
    if (flag < 0) return Outcome::kFailure;
    return Outcome::kReachedTime;
  }

  void root_info(int* found) override { call(sun::erk::get_root_info, mem_.get(), found); }

  void interpolate(double t, double* y) override {
    call(sun::erk::get_dky, mem_.get(), t, 0, dky_.get());
    store_dense(y);
  }

 private:
  SolverCounts segment() override {
    SolverCounts c;
    call(sun::erk::get_num_steps, mem_.get(), &c.steps);
    call(sun::erk::get_num_rhs_evals, mem_.get(), &c.rhs_evals);
    call(sun::erk::get_num_g_evals, mem_.get(), &c.root_evals);
    return settled(c);
  }

  ErkMemory mem_;
};

}  // namespace

std::unique_ptr<OdeIntegrator> make_cvode(const SolverSettings& s, OdeProblem& p, bool bdf) {
  return std::make_unique<CvodeIntegrator>(s, p, bdf);
}

std::unique_ptr<OdeIntegrator> make_arkode_erk(const SolverSettings& s, OdeProblem& p, int order) {
  if (order != 5 && order != 8) throw IntegratorError("ARKODE ERKStep: no table of order " + std::to_string(order));
  return std::make_unique<ErkIntegrator>(s, p, order == 5 ? ARKODE_DORMAND_PRINCE_7_4_5 : ARKODE_FEHLBERG_13_7_8);
}

}  // namespace pcrf::detail
