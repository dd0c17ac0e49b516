// Tregenza's and Reinhart's sky patches (see sky_patches.h).
#include "radiosity/climate/sky_patches.h"

#include "radiosity/sources/sky.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynrad::rad {

namespace {

constexpr int kTregenzaBand[7] = {30, 30, 24, 24, 18, 12, 6};
constexpr double kBand = 12 * M_PI / 180;  // each band's height

}  // namespace

SkyPatches::SkyPatches(int subdivision, const Vec3d& up, const Vec3d& north) : n_(subdivision) {
  if (subdivision < 1 || subdivision > 16)
    throw std::invalid_argument("sky patches: the subdivision must be 1 (Tregenza) to 16");
  up_ = up.normalized();
  north_ = (north - up_ * OpenMesh::dot(north, up_)).normalized();
  east_ = OpenMesh::cross(north_, up_);
  row_height_ = kBand / n_;
  first_.push_back(0);
  for (int band = 0; band < 7; ++band)
    for (int r = 0; r < n_; ++r) {
      per_row_.push_back(kTregenzaBand[band] * n_);
      first_.push_back(first_.back() + static_cast<std::size_t>(per_row_.back()));
    }
}

Vec3d SkyPatches::direction(double altitude, double azimuth) const {
  const double c = std::cos(altitude);
  return north_ * (c * std::cos(azimuth)) + east_ * (c * std::sin(azimuth)) + up_ * std::sin(altitude);
}

std::array<double, 2> SkyPatches::altitude_azimuth(const Vec3d& d) const {
  return {std::asin(std::clamp(OpenMesh::dot(d, up_), -1.0, 1.0)),
          std::atan2(OpenMesh::dot(d, east_), OpenMesh::dot(d, north_))};
}

std::size_t SkyPatches::index(const Vec3d& d) const {
  if (!(OpenMesh::dot(d, up_) > 0)) return ground();
  const auto [altitude, azimuth] = altitude_azimuth(d);
  const auto row = static_cast<std::size_t>(altitude / row_height_);
  if (row >= per_row_.size()) return first_.back();  // the cap
  const int count = per_row_[row];
  const double width = 2 * M_PI / count;
  // The first patch is centred on north: shift by half a patch.
  auto k = static_cast<long>(std::floor((azimuth + width / 2) / width));
  k = ((k % count) + count) % count;
  return first_[row] + static_cast<std::size_t>(k);
}

SkyPatches::Bounds SkyPatches::bounds(std::size_t i) const {
  if (i >= size()) return {-M_PI / 2, 0, 0, 2 * M_PI};
  if (i == first_.back()) return {per_row_.size() * row_height_, M_PI / 2, 0, 2 * M_PI};
  const auto row = static_cast<std::size_t>(std::upper_bound(first_.begin(), first_.end(), i) - first_.begin() - 1);
  const double width = 2 * M_PI / per_row_[row];
  const double k = static_cast<double>(i - first_[row]);
  return {row * row_height_, (row + 1) * row_height_, (k - 0.5) * width, (k + 0.5) * width};
}

double SkyPatches::solid_angle(std::size_t i) const {
  const Bounds b = bounds(i);
  if (i >= size()) return 2 * M_PI;
  return (b.azimuth1 - b.azimuth0) * (std::sin(b.altitude1) - std::sin(b.altitude0));
}

double SkyPatches::projected_solid_angle(std::size_t i) const {
  if (i >= size()) return 0;
  const Bounds b = bounds(i);
  const double s0 = std::sin(b.altitude0), s1 = std::sin(b.altitude1);
  return (b.azimuth1 - b.azimuth0) * (s1 * s1 - s0 * s0) / 2;
}

Vec3d SkyPatches::centre(std::size_t i) const {
  if (i >= size()) return -up_;
  if (i == first_.back()) return up_;
  const Bounds b = bounds(i);
  return direction((b.altitude0 + b.altitude1) / 2, (b.azimuth0 + b.azimuth1) / 2);
}

std::vector<double> sky_vector(const SkyPatches& patches, const SkyModel& sky, int side) {
  std::vector<double> out(patches.size() + 1, 0.0);
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const SkyPatches::Bounds b = patches.bounds(i);
    const double s0 = std::sin(b.altitude0), s1 = std::sin(b.altitude1);
    double sum = 0;
    for (int a = 0; a < side; ++a)
      for (int e = 0; e < side; ++e) {
        // Even in sin(altitude) and azimuth: equal solid angles.
        const double altitude = std::asin(s0 + (s1 - s0) * (a + 0.5) / side);
        const double azimuth = b.azimuth0 + (b.azimuth1 - b.azimuth0) * (e + 0.5) / side;
        sum += sky.luminance(patches.direction(altitude, azimuth));
      }
    out[i] = sum / (static_cast<double>(side) * side);
  }
  out[patches.ground()] = sky.ground_luminance;
  return out;
}

}  // namespace dynrad::rad
