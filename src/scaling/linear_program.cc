#include "scaling/linear_program.h"

#include <cmath>
#include <glpk.h>
#include <map>

namespace gearpatch {

namespace {

/// GLPK's bound type for lo <= x <= hi with infinite ends allowed.
int bound_type(double lo, double hi) {
  const bool low = std::isfinite(lo), high = std::isfinite(hi);
  if (low && high) return lo == hi ? GLP_FX : GLP_DB;
  if (low) return GLP_LO;
  if (high) return GLP_UP;
  return GLP_FR;
}

double finite_or_zero(double x) { return std::isfinite(x) ? x : 0.0; }

}  // namespace

namespace {
// GLPK keeps an environment per thread, made by its first call there and never
// freed by itself: a pool thread that solved a scaling would leak it at its end.
// The last problem of a thread frees it; the next call makes a new one.
thread_local int live_problems = 0;
}  // namespace

void LinearProgram::Deleter::operator()(glp_prob* p) const {
  glp_delete_prob(p);
  if (--live_problems == 0) glp_free_env();
}

LinearProgram::LinearProgram() : p_(glp_create_prob()) {
  ++live_problems;
  glp_term_out(GLP_OFF);
}
LinearProgram::~LinearProgram() = default;
LinearProgram::LinearProgram(LinearProgram&&) noexcept = default;
LinearProgram& LinearProgram::operator=(LinearProgram&&) noexcept = default;

int LinearProgram::add_column(const std::string& name, double lo, double hi, bool integer) {
  const int j = glp_add_cols(p_.get(), 1);
  glp_set_col_name(p_.get(), j, name.c_str());
  set_column_bounds(j, lo, hi);
  if (integer) {
    glp_set_col_kind(p_.get(), j, GLP_IV);
    integer_ = true;
  }
  return j;
}

void LinearProgram::set_column_bounds(int j, double lo, double hi) {
  glp_set_col_bnds(p_.get(), j, bound_type(lo, hi), finite_or_zero(lo), finite_or_zero(hi));
}

int LinearProgram::add_row(const std::string& name, const std::vector<std::pair<int, double>>& terms,
                           double lo, double hi) {
  const int i = glp_add_rows(p_.get(), 1);
  glp_set_row_name(p_.get(), i, name.c_str());
  glp_set_row_bnds(p_.get(), i, bound_type(lo, hi), finite_or_zero(lo), finite_or_zero(hi));
  std::map<int, double> merged;  // GLPK refuses a column twice in one row
  for (const auto& [column, coefficient] : terms) merged[column] += coefficient;
  std::vector<int> index{0};
  std::vector<double> value{0};
  for (const auto& [column, coefficient] : merged)
    if (coefficient != 0) {
      index.push_back(column);
      value.push_back(coefficient);
    }
  glp_set_mat_row(p_.get(), i, static_cast<int>(index.size()) - 1, index.data(), value.data());
  return i;
}

void LinearProgram::set_objective(const std::vector<std::pair<int, double>>& terms, bool maximise) {
  for (int j = 1; j <= columns(); ++j) glp_set_obj_coef(p_.get(), j, 0);
  for (const auto& [column, coefficient] : terms)
    glp_set_obj_coef(p_.get(), column, glp_get_obj_coef(p_.get(), column) + coefficient);
  glp_set_obj_dir(p_.get(), maximise ? GLP_MAX : GLP_MIN);
}

LinearProgram::Status LinearProgram::solve() {
  mip_solved_ = false;
  glp_smcp simplex;
  glp_init_smcp(&simplex);
  simplex.msg_lev = GLP_MSG_OFF;
  simplex.presolve = GLP_OFF;
  glp_adv_basis(p_.get(), 0);
  if (glp_simplex(p_.get(), &simplex) != 0) {
    simplex.presolve = GLP_ON;  // an ill-conditioned basis: let the presolver start afresh
    if (glp_simplex(p_.get(), &simplex) != 0) return Status::failed;
  }
  const int lp = glp_get_status(p_.get());
  if (lp == GLP_NOFEAS || lp == GLP_INFEAS) return Status::infeasible;
  if (lp == GLP_UNBND) return Status::unbounded;
  if (lp != GLP_OPT) return Status::failed;
  if (!integer_) return Status::optimal;
  glp_iocp branch;
  glp_init_iocp(&branch);
  branch.msg_lev = GLP_MSG_OFF;
  branch.tol_int = 1e-9;
  if (glp_intopt(p_.get(), &branch) != 0) return Status::failed;
  mip_solved_ = true;
  switch (glp_mip_status(p_.get())) {
    case GLP_OPT: return Status::optimal;
    case GLP_NOFEAS: return Status::infeasible;
    default: return Status::failed;
  }
}

double LinearProgram::objective() const {
  return mip_solved_ ? glp_mip_obj_val(p_.get()) : glp_get_obj_val(p_.get());
}

double LinearProgram::value(int j) const {
  return mip_solved_ ? glp_mip_col_val(p_.get(), j) : glp_get_col_prim(p_.get(), j);
}

double LinearProgram::row_activity(int i) const {
  return mip_solved_ ? glp_mip_row_val(p_.get(), i) : glp_get_row_prim(p_.get(), i);
}

bool LinearProgram::row_binds(int i, double tolerance) const {
  const int type = glp_get_row_type(p_.get(), i);
  const double x = row_activity(i);
  const bool low = (type == GLP_LO || type == GLP_DB || type == GLP_FX) &&
                   std::abs(x - glp_get_row_lb(p_.get(), i)) <= tolerance;
  const bool high = (type == GLP_UP || type == GLP_DB || type == GLP_FX) &&
                    std::abs(x - glp_get_row_ub(p_.get(), i)) <= tolerance;
  return low || high;
}

std::string LinearProgram::row_name(int i) const {
  const char* name = glp_get_row_name(p_.get(), i);
  return name ? name : "";
}

int LinearProgram::rows() const { return glp_get_num_rows(p_.get()); }
int LinearProgram::columns() const { return glp_get_num_cols(p_.get()); }

}  // namespace gearpatch
