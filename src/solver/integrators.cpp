// SUNDIALS adapters for the rocking ODE: CVODE (Adams / BDF) and ARKODE ERKStep.
#include "integrators.hpp"

#include <arkode/arkode_erkstep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <string>

namespace pcrf::detail {
namespace {

void check_flag(int flag, const char* call) {
  if (flag < 0) throw IntegratorError(std::string(call) + " failed with flag " + std::to_string(flag));
}
template <class T>
T* check_ptr(T* p, const char* call) {
  if (p == nullptr) throw IntegratorError(std::string(call) + " returned NULL");
  return p;
}

int rhs_thunk(realtype t, N_Vector y, N_Vector ydot, void* user) {
  return static_cast<OdeProblem*>(user)->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
}
int root_thunk(realtype t, N_Vector y, realtype* g, void* user) {
  return static_cast<OdeProblem*>(user)->roots(t, N_VGetArrayPointer(y), g);
}
int jac_thunk(realtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix J, void* user, N_Vector, N_Vector, N_Vector) {
  double dfdy[4];
  const int flag = static_cast<OdeProblem*>(user)->jacobian(t, N_VGetArrayPointer(y), dfdy);
  SM_ELEMENT_D(J, 0, 0) = dfdy[0];
  SM_ELEMENT_D(J, 0, 1) = dfdy[1];
  SM_ELEMENT_D(J, 1, 0) = dfdy[2];
  SM_ELEMENT_D(J, 1, 1) = dfdy[3];
  return flag;
}
// SUNDIALS reports errors through this handler instead of printing to stderr: a study
// of thousands of cases must not flood the terminal; the message lands in the result.
void error_thunk(int code, const char* module, const char* function, char* msg, void* data) {
  *static_cast<std::string*>(data) =
      std::string(module) + "::" + function + " (flag " + std::to_string(code) + "): " + msg;
}

/// Owns the SUNDIALS context and the state vector shared by both adapters.
class SundialsBase : public OdeIntegrator {
 protected:
  SundialsBase(const SolverSettings& s, OdeProblem& p) : settings_(s), problem_(p) {
    check_flag(SUNContext_Create(nullptr, &ctx_), "SUNContext_Create");
    y_ = check_ptr(N_VNew_Serial(2, ctx_), "N_VNew_Serial");
    atol_ = check_ptr(N_VNew_Serial(2, ctx_), "N_VNew_Serial");
    dky_ = check_ptr(N_VNew_Serial(2, ctx_), "N_VNew_Serial");
    N_VGetArrayPointer(atol_)[0] = s.atol_theta_rad;
    N_VGetArrayPointer(atol_)[1] = s.atol_omega_rad_s;
    N_VConst(0.0, y_);
  }
  ~SundialsBase() override {
    N_VDestroy(dky_);
    N_VDestroy(atol_);
    N_VDestroy(y_);
    SUNContext_Free(&ctx_);
  }
  void load(const double* y0) {
    N_VGetArrayPointer(y_)[0] = y0[0];
    N_VGetArrayPointer(y_)[1] = y0[1];
  }
  void store(double* y) const {
    y[0] = N_VGetArrayPointer(y_)[0];
    y[1] = N_VGetArrayPointer(y_)[1];
  }
  const std::string& last_error() const override { return error_; }

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
  SUNContext ctx_ = nullptr;
  N_Vector y_ = nullptr;
  N_Vector atol_ = nullptr;
  N_Vector dky_ = nullptr;  ///< dense output
  SolverCounts done_;  ///< counts of finished segments
  std::string error_;
  bool started_ = false;
};

class CvodeIntegrator final : public SundialsBase {
 public:
  CvodeIntegrator(const SolverSettings& s, OdeProblem& p, bool bdf) : SundialsBase(s, p) {
    mem_ = check_ptr(CVodeCreate(bdf ? CV_BDF : CV_ADAMS, ctx_), "CVodeCreate");
    check_flag(CVodeInit(mem_, rhs_thunk, 0.0, y_), "CVodeInit");
    check_flag(CVodeSetUserData(mem_, &problem_), "CVodeSetUserData");
    check_flag(CVodeSVtolerances(mem_, s.rtol, atol_), "CVodeSVtolerances");
    check_flag(CVodeSetErrHandlerFn(mem_, error_thunk, &error_), "CVodeSetErrHandlerFn");
    check_flag(CVodeSetMaxNumSteps(mem_, s.max_steps), "CVodeSetMaxNumSteps");
    check_flag(CVodeSetMaxErrTestFails(mem_, 50), "CVodeSetMaxErrTestFails");
    if (s.max_step_s > 0) check_flag(CVodeSetMaxStep(mem_, s.max_step_s), "CVodeSetMaxStep");
    check_flag(CVodeRootInit(mem_, p.root_count(), root_thunk), "CVodeRootInit");
    check_flag(CVodeSetNoInactiveRootWarn(mem_), "CVodeSetNoInactiveRootWarn");
    if (bdf) {
      A_ = check_ptr(SUNDenseMatrix(2, 2, ctx_), "SUNDenseMatrix");
      LS_ = check_ptr(SUNLinSol_Dense(y_, A_, ctx_), "SUNLinSol_Dense");
      check_flag(CVodeSetLinearSolver(mem_, LS_, A_), "CVodeSetLinearSolver");
      if (p.has_jacobian()) check_flag(CVodeSetJacFn(mem_, jac_thunk), "CVodeSetJacFn");
    } else {
      NLS_ = check_ptr(SUNNonlinSol_FixedPoint(y_, 0, ctx_), "SUNNonlinSol_FixedPoint");
      check_flag(CVodeSetNonlinearSolver(mem_, NLS_), "CVodeSetNonlinearSolver");
    }
  }
  ~CvodeIntegrator() override {
    CVodeFree(&mem_);
    if (LS_) SUNLinSolFree(LS_);
    if (A_) SUNMatDestroy(A_);
    if (NLS_) SUNNonlinSolFree(NLS_);
  }

  void restart(double t0, const double* y0, const int* root_dirs, double t_stop, double h0) override {
    accumulate();
    load(y0);
    check_flag(CVodeReInit(mem_, t0, y_), "CVodeReInit");
    check_flag(CVodeSetInitStep(mem_, h0), "CVodeSetInitStep");
    check_flag(CVodeSetStopTime(mem_, t_stop), "CVodeSetStopTime");
    check_flag(CVodeSetRootDirection(mem_, const_cast<int*>(root_dirs)), "CVodeSetRootDirection");
    done_.reinits += started_ ? 1 : 0;
    started_ = true;
  }

  void set_stop_time(double t_stop) override { check_flag(CVodeSetStopTime(mem_, t_stop), "CVodeSetStopTime"); }

  Outcome advance(double tout, double& t, double* y, bool one_step) override {
    realtype tret = t;
    const int flag = CVode(mem_, tout, y_, &tret, one_step ? CV_ONE_STEP : CV_NORMAL);
    t = tret;
    store(y);
    if (flag == CV_ROOT_RETURN) return Outcome::kRoot;
    if (flag < 0) return Outcome::kFailure;
    return Outcome::kReachedTime;
  }

  void root_info(int* found) override { check_flag(CVodeGetRootInfo(mem_, found), "CVodeGetRootInfo"); }

  void interpolate(double t, double* y) override {
    check_flag(CVodeGetDky(mem_, t, 0, dky_), "CVodeGetDky");
    y[0] = N_VGetArrayPointer(dky_)[0];
    y[1] = N_VGetArrayPointer(dky_)[1];
  }

 private:
  SolverCounts segment() override {
    SolverCounts c;
    long nfe_ls = 0;
    CVodeGetNumSteps(mem_, &c.steps);
    CVodeGetNumRhsEvals(mem_, &c.rhs_evals);
    if (LS_) CVodeGetNumLinRhsEvals(mem_, &nfe_ls);
    c.rhs_evals += nfe_ls;
    CVodeGetNumGEvals(mem_, &c.root_evals);
    return settled(c);
  }

  void* mem_ = nullptr;
  SUNMatrix A_ = nullptr;
  SUNLinearSolver LS_ = nullptr;
  SUNNonlinearSolver NLS_ = nullptr;
};

class ErkIntegrator final : public SundialsBase {
 public:
  ErkIntegrator(const SolverSettings& s, OdeProblem& p, ARKODE_ERKTableID table) : SundialsBase(s, p) {
    mem_ = check_ptr(ERKStepCreate(rhs_thunk, 0.0, y_, ctx_), "ERKStepCreate");
    check_flag(ERKStepSetTableNum(mem_, table), "ERKStepSetTableNum");
    check_flag(ERKStepSetUserData(mem_, &problem_), "ERKStepSetUserData");
    check_flag(ERKStepSVtolerances(mem_, s.rtol, atol_), "ERKStepSVtolerances");
    check_flag(ERKStepSetErrHandlerFn(mem_, error_thunk, &error_), "ERKStepSetErrHandlerFn");
    check_flag(ERKStepSetMaxNumSteps(mem_, s.max_steps), "ERKStepSetMaxNumSteps");
    // A step across a record sample meets a kink in ü_g (linear interpolation): the
    // error test may fail many times before the step is small enough; the default of
    // 7 failures (each cutting h by at most 0.3) gives up too early for 8th order.
    check_flag(ERKStepSetMaxErrTestFails(mem_, 50), "ERKStepSetMaxErrTestFails");
    if (s.max_step_s > 0) check_flag(ERKStepSetMaxStep(mem_, s.max_step_s), "ERKStepSetMaxStep");
    check_flag(ERKStepRootInit(mem_, p.root_count(), root_thunk), "ERKStepRootInit");
    check_flag(ERKStepSetNoInactiveRootWarn(mem_), "ERKStepSetNoInactiveRootWarn");
  }
  ~ErkIntegrator() override { ERKStepFree(&mem_); }

  void restart(double t0, const double* y0, const int* root_dirs, double t_stop, double h0) override {
    accumulate();
    load(y0);
    check_flag(ERKStepReInit(mem_, rhs_thunk, t0, y_), "ERKStepReInit");
    check_flag(ERKStepSetInitStep(mem_, h0), "ERKStepSetInitStep");
    check_flag(ERKStepSetStopTime(mem_, t_stop), "ERKStepSetStopTime");
    check_flag(ERKStepSetRootDirection(mem_, const_cast<int*>(root_dirs)), "ERKStepSetRootDirection");
    done_.reinits += started_ ? 1 : 0;
    started_ = true;
  }

  void set_stop_time(double t_stop) override {
    check_flag(ERKStepSetStopTime(mem_, t_stop), "ERKStepSetStopTime");
  }

  Outcome advance(double tout, double& t, double* y, bool one_step) override {
    realtype tret = t;
    const int flag = ERKStepEvolve(mem_, tout, y_, &tret, one_step ? ARK_ONE_STEP : ARK_NORMAL);
    t = tret;
    store(y);
    if (flag == ARK_ROOT_RETURN) return Outcome::kRoot;
    if (flag < 0) return Outcome::kFailure;
    return Outcome::kReachedTime;
  }

  void root_info(int* found) override { check_flag(ERKStepGetRootInfo(mem_, found), "ERKStepGetRootInfo"); }

  void interpolate(double t, double* y) override {
    check_flag(ERKStepGetDky(mem_, t, 0, dky_), "ERKStepGetDky");
    y[0] = N_VGetArrayPointer(dky_)[0];
    y[1] = N_VGetArrayPointer(dky_)[1];
  }

 private:
  SolverCounts segment() override {
    SolverCounts c;
    ERKStepGetNumSteps(mem_, &c.steps);
    ERKStepGetNumRhsEvals(mem_, &c.rhs_evals);
    ERKStepGetNumGEvals(mem_, &c.root_evals);
    return settled(c);
  }

  void* mem_ = nullptr;
};

}  // namespace

std::unique_ptr<OdeIntegrator> make_integrator(const SolverSettings& s, OdeProblem& p) {
  switch (s.integrator) {
    case Integrator::kCvodeBdf: return std::make_unique<CvodeIntegrator>(s, p, true);
    case Integrator::kCvodeAdams: return std::make_unique<CvodeIntegrator>(s, p, false);
    case Integrator::kArkodeErk5: return std::make_unique<ErkIntegrator>(s, p, ARKODE_DORMAND_PRINCE_7_4_5);
    case Integrator::kArkodeErk8: return std::make_unique<ErkIntegrator>(s, p, ARKODE_FEHLBERG_13_7_8);
    case Integrator::kFixedRk4SignChange: break;  // not a SUNDIALS method: see fixed_step_solver.cpp
  }
  throw IntegratorError("unknown integrator");
}

}  // namespace pcrf::detail
