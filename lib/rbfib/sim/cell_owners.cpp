#include "rbfib/sim/cell_owners.hpp"

#include <thrust/copy.h>

#include <cmath>

namespace rbfib::sim {

std::vector<CellRecord> cell_records(const cells::Batch& batch, const std::vector<index_t>& ids) {
  std::vector<CellRecord> out = records_of(batch.state().to_host(), batch.body_force(), batch.type().n_data());
  for (std::size_t c = 0; c < out.size(); ++c) out[c].id = ids[c];
  return out;
}

std::vector<double> state_of(const std::vector<CellRecord>& cells, index_t nd) {
  const index_t N = index_t(cells.size());
  std::vector<double> state(static_cast<std::size_t>(6 * N * nd));
  for (index_t c = 0; c < N; ++c)
    for (int k = 0; k < 6; ++k) {
      const index_t column = k * N + c;  // X: a N + c, U: (3 + a) N + c
      const std::vector<double>& s = cells[static_cast<std::size_t>(c)].state;
      std::copy(s.begin() + k * nd, s.begin() + (k + 1) * nd, state.begin() + column * nd);
    }
  return state;
}

cells::Batch batch_of(const std::shared_ptr<const cells::CellType>& type, const std::vector<CellRecord>& cells) {
  const index_t N = index_t(cells.size());
  std::vector<double> body(static_cast<std::size_t>(3 * N));
  for (index_t c = 0; c < N; ++c)
    for (int d = 0; d < 3; ++d) body[static_cast<std::size_t>(d * N + c)] = cells[static_cast<std::size_t>(c)].body[d];
  return cells::Batch::from_state(type, N, state_of(cells, type->n_data()), body);
}

std::vector<CellRecord> records_of(const std::vector<double>& state, const std::vector<double>& body, index_t nd) {
  const index_t N = index_t(state.size()) / (6 * nd);
  std::vector<CellRecord> out(static_cast<std::size_t>(N));
  for (index_t c = 0; c < N; ++c) {
    CellRecord& r = out[static_cast<std::size_t>(c)];
    r.id = c;
    r.state.resize(static_cast<std::size_t>(6 * nd));
    for (int k = 0; k < 6; ++k) {
      const index_t column = k * N + c;  // X: a N + c, U: (3 + a) N + c
      std::copy(state.begin() + column * nd, state.begin() + (column + 1) * nd, r.state.begin() + k * nd);
    }
    for (int d = 0; d < 3; ++d) r.body[d] = body[static_cast<std::size_t>(d * N + c)];
  }
  return out;
}

double site_mean(const CellRecord& cell, int axis, index_t nd) {
  double s = 0;
  for (index_t i = 0; i < nd; ++i) s += cell.state[static_cast<std::size_t>(axis * nd + i)];
  return std::isfinite(s) ? s / double(nd) : NAN;
}

std::vector<double> site_means(const cells::Batch& batch, int axis) {
  const index_t nd = batch.type().n_data(), N = batch.size();
  const dvec& state = batch.state().storage();
  std::vector<double> x(static_cast<std::size_t>(nd * N));  // columns axis N + c, c < N: contiguous
  thrust::copy(state.begin() + axis * N * nd, state.begin() + (axis + 1) * N * nd, x.begin());
  std::vector<double> mean(static_cast<std::size_t>(N));
  for (index_t c = 0; c < N; ++c) {
    double s = 0;
    for (index_t i = 0; i < nd; ++i) s += x[static_cast<std::size_t>(c * nd + i)];
    mean[static_cast<std::size_t>(c)] = std::isfinite(s) ? s / double(nd) : NAN;
  }
  return mean;
}

void pack(const CellRecord& cell, index_t batch, std::vector<double>& message) {
  message.push_back(double(batch));
  message.push_back(double(cell.id));
  message.insert(message.end(), cell.state.begin(), cell.state.end());
  message.insert(message.end(), cell.body.begin(), cell.body.end());
}

}  // namespace rbfib::sim
