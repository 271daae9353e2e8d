#pragma once
/// Host copies of engine arrays in the scalars the host side works in: state arrays (in the
/// state scalar P) and force arrays (in the law's scalar) to and from Real, and contact history
/// values to and from Real.
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "engine/DeviceArray.hpp"

namespace gpudem {

/// `host` with f applied to each element.
template <class T, class F>
auto converted(const std::vector<T>& host, F f) {
  std::vector<decltype(f(host.front()))> out;
  out.reserve(host.size());
  for (const T& value : host) out.push_back(f(value));
  return out;
}

/// Host copy of a 4-wide state array, in Real.
template <class Space, class P>
std::vector<Real4> download_in_real(const DeviceArray<Vec4T<P>, Space>& a) {
  std::vector<Vec4T<P>> host;
  a.download(host);
  if constexpr (std::is_same_v<P, Real>)
    return host;
  else
    return converted(host, vec4_cast<Real, P>);
}

/// Uploads host values in Real into a 4-wide array of scalar S, rounded to S.
template <class Space, class S>
void upload_rounded(const std::vector<Real4>& host, DeviceArray<Vec4T<S>, Space>& a) {
  if constexpr (std::is_same_v<S, Real>)
    a.upload(host);
  else
    a.upload(converted(host, vec4_cast<S, Real>));
}

/// Uploads host vectors in Real into an array of scalar S, rounded to S.
template <class Space, class S>
void upload_rounded(const std::vector<Vec3>& host, DeviceArray<Vec3T<S>, Space>& a) {
  if constexpr (std::is_same_v<S, Real>)
    a.upload(host);
  else
    a.upload(converted(host, vec_cast<S, Real>));
}

/// Host copy of a history array (records of the law's width, in its scalar S), in Real.
template <class S, class Space>
std::vector<Real> history_in_real(const DeviceArray<S, Space>& history) {
  std::vector<S> host;
  history.download(host);
  return std::vector<Real>(host.begin(), host.end());
}

/// Uploads history values in Real into a history array of scalar S, rounded to S.
template <class S, class Space>
void upload_history(const std::vector<Real>& values, DeviceArray<S, Space>& history) {
  history.upload(std::vector<S>(values.begin(), values.end()));
}

}  // namespace gpudem
