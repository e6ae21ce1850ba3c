#include "siconos_lemke.hpp"

#include <cstring>

#include "LCP_Solvers.h"
#include "LinearComplementarityProblem.h"
#include "NumericsMatrix.h"
#include "SolverOptions.h"
#include "lcp_cst.h"

struct SiconosLemke::Data {
  LinearComplementarityProblem problem{};
  Eigen::VectorXd q;
  SolverOptions* options = nullptr;
};

SiconosLemke::SiconosLemke(const Eigen::MatrixXd& M, const Eigen::VectorXd& q)
    : data_(new Data) {
  const int n = static_cast<int>(q.size());
  data_->q = q;
  data_->problem.size = n;
  data_->problem.M = NM_create(NM_DENSE, n, n);
  std::memcpy(data_->problem.M->matrix0, M.data(), sizeof(double) * n * n);
  data_->problem.q = data_->q.data();
  data_->options = solver_options_create(SICONOS_LCP_LEMKE);
}

SiconosLemke::~SiconosLemke() {
  solver_options_delete(data_->options);
  NM_free(data_->problem.M);
}

int SiconosLemke::solve(Eigen::VectorXd& z, Eigen::VectorXd& w) {
  int info = -1;
  lcp_lexicolemke(&data_->problem, z.data(), w.data(), &info, data_->options);
  return info;
}

int SiconosLemke::pivots() const { return data_->options->iparam[SICONOS_IPARAM_ITER_DONE]; }
