#include "rbfib/cells/cell_type.hpp"

#include "rbfib/core/error.hpp"
#include "rbfib/surface/geometry.hpp"
#include "rbfib/surface/quadrature.hpp"

#include <thrust/copy.h>

#include <cmath>

namespace rbfib::cells {

std::string ForceModel::describe() const {
  std::string s;
  for (const auto& e : elastic) {
    std::string p;
    for (const mechanics::EnergyDensity::Parameter& q : e.parameters())
      p += (p.empty() ? "" : ", ") + std::string(q.name) + " = " + to_text(q.value) + (*q.units ? std::string(" ") + q.units : "");
    s += (s.empty() ? "" : " + ") + e.name() + " (" + p + ")";
  }
  if (bending())
    s += (s.empty() ? "" : " + ") + std::string("bending (kappa = ") + to_text(kappa) + " erg, H' = " +
         (H0_reference ? std::string("reference curvature") : to_text(H0) + " 1/cm") + ")";
  if (dissipation()) s += (s.empty() ? "" : " + ") + std::string("dissipation (nu = ") + to_text(nu) + " dyn s/cm)";
  return s.empty() ? "no forces" : s;
}

namespace {
/// Jets of one cell (`cols` columns of X) at the operator rows [row0, row0 + rows), on the device.
void one_cell_jets(const surface::SurfaceOperators& ops, const linalg::DeviceMatrix& X, index_t row0, index_t rows,
                   linalg::DeviceMatrix& V, linalg::DeviceMatrix& D) {
  V.resize(rows, X.cols());
  D.resize(surface::derivative_count * rows, X.cols());
  surface::OperatorWorkspace work;
  surface::apply_operators_rows(ops, X.view(), row0, rows, V.view(), D.view(), work);
}
}  // namespace

CellType::CellType(CellTypeSpec spec) : spec_(std::move(spec)) {
  const std::string& nm = spec_.name;
  require(!nm.empty(), "cell type name", "''", "must not be empty");
  require(bool(spec_.shape.position), "cell type '" + nm + "' reference shape", "none", "must be given");
  const ForceModel& m = spec_.model;
  require(int(m.elastic.size()) <= ForceModel::max_elastic_energies, "cell type '" + nm + "' elastic energies",
          m.elastic.size(), "at most " + to_text(ForceModel::max_elastic_energies));
  require(m.kappa >= 0, "cell type '" + nm + "' bending modulus kappa (erg)", m.kappa, "must be >= 0");
  require(m.nu >= 0, "cell type '" + nm + "' membrane viscosity nu (dyn s/cm)", m.nu, "must be >= 0");
  require(std::isfinite(m.H0), "cell type '" + nm + "' spontaneous curvature H' (1/cm)", m.H0, "must be finite");
  require(n_sample() > 0, "cell type '" + nm + "' sample sites", n_sample(), "must be > 0");

  // 1. Operators (host build, one upload): sample sites, then the data sites with bending.
  const index_t nd = n_data(), ns = n_sample();
  surface::SphereSites eval = spec_.sample_sites;
  if (m.bending()) {
    eval.lambda.insert(eval.lambda.end(), spec_.data_sites.lambda.begin(), spec_.data_sites.lambda.end());
    eval.theta.insert(eval.theta.end(), spec_.data_sites.theta.begin(), spec_.data_sites.theta.end());
  }
  if (spec_.interpolant == Interpolant::spherical_harmonics)
    operators_ = surface::sh_operators(spec_.data_sites, eval, spec_.sh_degree);
  else
    operators_ = surface::rbf_operators(spec_.data_sites, eval, spec_.basis);
  // Single-precision products (surface/operators.hpp): the reference jets below come from the same
  // products, so that the reference shape carries no strain beyond their rounding.
  if (spec_.single_precision_products) operators_ = surface::in_single_precision(*operators_);

  // 2. Reference configuration at the data sites, n_d x 3.
  reference_host_.assign(static_cast<std::size_t>(3 * nd), 0.0);
  for (index_t i = 0; i < nd; ++i) {
    double x[3];
    spec_.shape.position(spec_.data_sites.lambda[i], spec_.data_sites.theta[i], x);
    for (int d = 0; d < 3; ++d) {
      require(std::isfinite(x[d]), "cell type '" + nm + "' reference shape at data site " + to_text(i), x[d],
              "must be finite");
      reference_host_[d * nd + i] = x[d];
    }
  }
  reference_data_ = linalg::DeviceMatrix::from_host(nd, 3, reference_host_.data());

  // 3. Reference jets Z at the sample sites, and the weights of eq. (51).
  one_cell_jets(*operators_, reference_data_, 0, ns, Z_value_, Z_derivatives_);
  const std::vector<surface::Jet> Z = reference_jets_host();
  std::vector<double> w = spec_.sphere_weights;
  if (w.empty()) w = surface::rbf_sphere_weights(spec_.sample_sites, 1).w;
  require(static_cast<index_t>(w.size()) == ns, "cell type '" + nm + "' sphere weights", w.size(),
          "must number the sample sites (" + to_text(ns) + ")");
  std::vector<double> det0(static_cast<std::size_t>(ns)), x_dot_n(static_cast<std::size_t>(ns));
  for (index_t i = 0; i < ns; ++i) {
    const surface::PointGeometry g = surface::point_geometry(Z[i]);
    if (!(g.det_g > 0))
      throw NumericalError(Cause::degenerate_site, "cell type '" + nm + "': reference surface degenerate at sample site " + to_text(i) +
                           " (det G0 = " + to_text(g.det_g) + ")");
    det0[i] = g.det_g;
    x_dot_n[i] = surface::dot3(Z[i].x, g.n);
  }
  const std::vector<double> dA0 = surface::reference_shape_weights(spec_.sample_sites, w, det0);
  for (index_t i = 0; i < ns; ++i) {
    area0_ += dA0[i];
    volume0_ += x_dot_n[i] * dA0[i] / 3;
  }
  dA0_.assign(dA0.begin(), dA0.end());

  // 4. Material spontaneous curvature: H of the reference at the data sites, and its jets.
  if (m.bending() && m.H0_reference) {
    linalg::DeviceMatrix V, D;
    one_cell_jets(*operators_, reference_data_, ns, nd, V, D);
    const std::vector<surface::Jet> Zd = surface::jets_on_host(V, D);
    std::vector<double> H(static_cast<std::size_t>(nd));
    for (index_t i = 0; i < nd; ++i) H[i] = surface::point_geometry(Zd[i]).H;
    H0_data_.assign(H.begin(), H.end());
    const linalg::DeviceMatrix Hd = linalg::DeviceMatrix::from_host(nd, 1, H.data());
    one_cell_jets(*operators_, Hd, 0, ns, H0_value_, H0_derivatives_);
  }
}

const surface::SurfaceOperators& CellType::to_sample() const {
  if (!model().bending()) return *operators_;
  if (!to_sample_) to_sample_ = surface::select_sample_sites(*operators_, 0, n_sample());
  return *to_sample_;
}

const surface::SurfaceOperators* CellType::at_data() const {
  if (!model().bending()) return nullptr;
  if (!at_data_) at_data_ = surface::select_sample_sites(*operators_, n_sample(), n_data());
  return at_data_.get();
}

surface::JetView CellType::reference_jets() const {
  const index_t ns = n_sample();
  return {ptr(Z_value_.storage()), ns, ptr(Z_derivatives_.storage()), surface::derivative_count * ns, ns, 1};
}

std::vector<surface::Jet> CellType::reference_jets_host() const { return surface::jets_on_host(Z_value_, Z_derivatives_); }

std::vector<double> CellType::dA0_host() const {
  std::vector<double> h(dA0_.size());
  thrust::copy(dA0_.begin(), dA0_.end(), h.begin());
  return h;
}

surface::JetView CellType::H0_jets() const {
  const index_t ns = n_sample();
  if (H0_value_.empty()) return {};
  return {ptr(H0_value_.storage()), ns, ptr(H0_derivatives_.storage()), surface::derivative_count * ns, ns, 1};
}

std::size_t CellType::bytes() const {
  std::size_t b = operators_->bytes();
  b += reference_data_.bytes() + Z_value_.bytes() + Z_derivatives_.bytes() + H0_value_.bytes() + H0_derivatives_.bytes();
  b += (dA0_.size() + H0_data_.size()) * sizeof(double);
  return b;
}

std::string CellType::describe() const {
  const std::string interpolant = spec_.interpolant == Interpolant::spherical_harmonics
                                     ? "spherical harmonics of degree " + to_text(spec_.sh_degree) + " (factored)"
                                     : "PHS r^" + to_text(spec_.basis.power) + " with harmonics of degree <= " +
                                           to_text(spec_.basis.sh_degree);
  return "cell type '" + name() + "': " + spec_.shape.name + "; " + to_text(n_data()) + " data sites, " +
         to_text(n_sample()) + " sample sites; " + interpolant +
         (model().bending() ? " (operators also evaluate at the data sites, for H)" : "") +
         (spec_.single_precision_products ? "; products in single precision" : "") +
         "\n  forces: " + model().describe() +
         "\n  reference area " + to_text(area0_ * 1e8) + " um^2, volume " + to_text(volume0_ * 1e12) +
         " um^3; device memory " + to_text(double(bytes()) / 1048576.0) + " MiB";
}

ProductFlops product_flops(const CellTypeSpec& spec, index_t N) {
  const double nd = double(spec.data_sites.size()), ns = double(spec.sample_sites.size());
  const double nj = ns + (spec.model.bending() ? nd : 0.0);  // the operators' rows: n_s, and n_d with bending
  ProductFlops f;
  const double X = 3.0 * double(N), U = spec.model.dissipation() ? 3.0 * double(N) : 0.0;
  // the sample sites' rows: value and derivatives of X, derivatives of U; the data sites' rows
  // (bending): derivatives of X
  f.jets = 2.0 * ns * nd * (6.0 * X + 5.0 * U) + 2.0 * 5.0 * (nj - ns) * nd * X;
  const double word = spec.single_precision_products ? 4.0 : 8.0;  // bytes per operator entry
  f.bytes = word * (6.0 * ns + 5.0 * (nj - ns)) * nd;
  if (spec.model.bending())  // H - H' rides through the sample sites' pass: its five derivatives
    f.bending = 2.0 * 5.0 * ns * nd * double(N);
  return f;
}

}  // namespace rbfib::cells
