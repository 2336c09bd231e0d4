#include "offshore_gnc/perception/target_tracker.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace perception {

const ParamTable<TrackerParams>& TrackerParams::table() {
  using P = TrackerParams;
  static const ParamTable<P> t = ParamTable<P>()
      .number("accel_sigma", &P::accel_sigma, 0.0, 50.0, "m/s^2",
              "white acceleration of the constant-velocity model (a boat changing course or speed)")
      .number("position_sigma", &P::position_sigma, 0.001, 100.0, "m", "a target position's noise per axis")
      .number("extent_share", &P::extent_share, 0.0, 1.0, "",
              "share of a target's extent added to that (its returns' centroid moves along a hull as it turns)")
      .number("initial_speed_sigma", &P::initial_speed_sigma, 0.01, 100.0, "m/s",
              "a newborn track's velocity uncertainty per axis")
      .number("gate", &P::gate, 0.5, 100.0, "",
              "Mahalanobis distance from a track's predicted position within which it may take a target")
      .integer("confirm_hits", &P::confirm_hits, 1, 1000, "updates (the first detection included) that confirm a track")
      .number("drop_time", &P::drop_time, 0.0, 3600.0, "s", "a confirmed track unseen this long is dropped")
      .number("tentative_drop_time", &P::tentative_drop_time, 0.0, 3600.0, "s",
              "a tentative track unseen this long is dropped (clutter)");
  return t;
}

void TrackerParams::validate() const { table().validate(*this); }

std::vector<int> assignLeastCost(const std::vector<std::vector<double>>& cost, double unpaired, double forbidden) {
  const std::size_t rows = cost.size(), cols = rows ? cost[0].size() : 0;
  std::vector<int> out(rows, -1);
  if (rows == 0 || cols == 0) return out;
  // Square problem of rows + cols: each row may instead take its own dummy column, each column its own dummy row, at
  // `unpaired`; dummies pair with each other for nothing. Forbidden pairs cost more than every other choice together.
  const std::size_t n = rows + cols;
  const double big = 1e6 * (1.0 + unpaired) * static_cast<double>(n);
  auto a = [&](std::size_t i, std::size_t j) -> double {  // 0-based
    if (i < rows && j < cols) return cost[i][j] >= forbidden ? big : cost[i][j];
    if (i < rows) return j - cols == i ? unpaired : big;
    if (j < cols) return i - rows == j ? unpaired : big;
    return 0.0;
  };
  // Kuhn-Munkres with potentials, 1-based (p[j]: the row given column j; way: the augmenting path)
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0.0), v(n + 1, 0.0);
  std::vector<std::size_t> p(n + 1, 0), way(n + 1, 0);
  for (std::size_t i = 1; i <= n; ++i) {
    p[0] = i;
    std::size_t j0 = 0;
    std::vector<double> minv(n + 1, inf);
    std::vector<bool> used(n + 1, false);
    do {
      used[j0] = true;
      const std::size_t i0 = p[j0];
      double delta = inf;
      std::size_t j1 = 0;
      for (std::size_t j = 1; j <= n; ++j) {
        if (used[j]) continue;
        const double cur = a(i0 - 1, j - 1) - u[i0] - v[j];
        if (cur < minv[j]) minv[j] = cur, way[j] = j0;
        if (minv[j] < delta) delta = minv[j], j1 = j;
      }
      for (std::size_t j = 0; j <= n; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      const std::size_t j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  for (std::size_t j = 1; j <= n; ++j) {
    const std::size_t i = p[j] - 1, c = j - 1;
    if (i < rows && c < cols && cost[i][c] < forbidden) out[i] = static_cast<int>(c);
  }
  return out;
}

TargetTracker::TargetTracker(const TrackerParams& p) : p_(p) {
  p_.validate();
  for (const char* c : {"non_finite_detection", "non_finite_time", "time_backwards"}) counters_.increment(c, 0);
}

Eigen::Matrix2d TargetTracker::noise(double length, double width) const {
  const double s = p_.position_sigma + p_.extent_share * std::max(length, width);
  return s * s * Eigen::Matrix2d::Identity();
}

void TargetTracker::predict(Track& tr, double t) const {
  const double dt = t - tr.t;
  if (dt <= 0.0) return;
  Eigen::Matrix4d F = Eigen::Matrix4d::Identity();
  F.topRightCorner<2, 2>() = dt * Eigen::Matrix2d::Identity();
  // the discrete white-noise acceleration model: one acceleration held over the step, per axis
  const double q = p_.accel_sigma * p_.accel_sigma;
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  Q.topLeftCorner<2, 2>() = q * dt * dt * dt * dt / 4.0 * Eigen::Matrix2d::Identity();
  Q.topRightCorner<2, 2>() = Q.bottomLeftCorner<2, 2>() = q * dt * dt * dt / 2.0 * Eigen::Matrix2d::Identity();
  Q.bottomRightCorner<2, 2>() = q * dt * dt * Eigen::Matrix2d::Identity();
  tr.x = F * tr.x;
  tr.P = F * tr.P * F.transpose() + Q;
  tr.t = t;
}

bool TargetTracker::update(double t, const std::vector<Detection>& detections) {
  if (!std::isfinite(t)) {
    counters_.increment("non_finite_time");
    return false;
  }
  if (started_ && t < last_t_) {
    counters_.increment("time_backwards");
    counters_.increment("tracks_dropped", tracks_.size());
    tracks_.clear();
  }
  started_ = true;
  last_t_ = t;

  std::vector<std::size_t> valid;
  for (std::size_t k = 0; k < detections.size(); ++k) {
    const Detection& d = detections[k];
    if (d.position.allFinite() && std::isfinite(d.length) && std::isfinite(d.width)) valid.push_back(k);
    else counters_.increment("non_finite_detection");
  }
  for (Track& tr : tracks_) {
    predict(tr, t);
    tr.detection = -1;
  }

  // each track against each target: the squared Mahalanobis distance of the target from its predicted position
  const double gate2 = p_.gate * p_.gate, forbidden = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> cost(tracks_.size(), std::vector<double>(valid.size(), forbidden));
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    const Track& tr = tracks_[i];
    for (std::size_t k = 0; k < valid.size(); ++k) {
      const Detection& d = detections[valid[k]];
      const Eigen::Matrix2d S = tr.P.topLeftCorner<2, 2>() + noise(d.length, d.width);
      const Eigen::Vector2d y = d.position - tr.position();
      const double d2 = y.dot(S.llt().solve(y));
      if (d2 <= gate2) cost[i][k] = d2;
    }
  }
  const std::vector<int> pick = assignLeastCost(cost, gate2, forbidden);

  std::vector<bool> taken(valid.size(), false);
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    if (pick[i] < 0) continue;
    Track& tr = tracks_[i];
    const Detection& d = detections[valid[pick[i]]];
    taken[pick[i]] = true;
    // Kalman update on the position (Joseph form: the covariance stays symmetric and positive)
    const Eigen::Matrix2d R = noise(d.length, d.width);
    Eigen::Matrix<double, 2, 4> H = Eigen::Matrix<double, 2, 4>::Zero();
    H.leftCols<2>().setIdentity();
    const Eigen::Matrix2d S = H * tr.P * H.transpose() + R;
    const Eigen::Matrix<double, 4, 2> K = tr.P * H.transpose() * S.inverse();
    tr.x += K * (d.position - tr.position());
    const Eigen::Matrix4d I_KH = Eigen::Matrix4d::Identity() - K * H;
    tr.P = I_KH * tr.P * I_KH.transpose() + K * R * K.transpose();
    tr.last_seen = t;
    ++tr.hits;
    tr.length = d.length;
    tr.width = d.width;
    tr.detection = static_cast<int>(valid[pick[i]]);
    if (!tr.confirmed && tr.hits >= p_.confirm_hits) {
      tr.confirmed = true;
      counters_.increment("tracks_confirmed");
    }
  }

  const auto before = tracks_.size();
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [&](const Track& tr) {
                                 return t - tr.last_seen > (tr.confirmed ? p_.drop_time : p_.tentative_drop_time);
                               }),
                tracks_.end());
  counters_.increment("tracks_dropped", before - tracks_.size());

  for (std::size_t k = 0; k < valid.size(); ++k) {  // a target no track took: a new track
    if (taken[k]) continue;
    const Detection& d = detections[valid[k]];
    Track tr;
    tr.id = next_id_++;
    tr.x << d.position, 0.0, 0.0;
    tr.P.setZero();
    tr.P.topLeftCorner<2, 2>() = noise(d.length, d.width);
    tr.P.bottomRightCorner<2, 2>() = p_.initial_speed_sigma * p_.initial_speed_sigma * Eigen::Matrix2d::Identity();
    tr.born = tr.last_seen = tr.t = t;
    tr.hits = 1;
    tr.confirmed = p_.confirm_hits <= 1;
    tr.length = d.length;
    tr.width = d.width;
    tr.detection = static_cast<int>(valid[k]);
    tracks_.push_back(tr);
    counters_.increment("tracks_born");
    if (tr.confirmed) counters_.increment("tracks_confirmed");
  }
  return true;
}

}  // namespace perception
}  // namespace offshore_gnc
