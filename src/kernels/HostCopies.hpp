#pragma once
/// Host copies of engine arrays in the scalars the host side works in: state arrays (in the
/// state scalar P) and force arrays (in the law's scalar) to and from Real, and contact history
/// records to and from flat rows of values.
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "core/Config.hpp"
#include "core/Vec3.hpp"
#include "kernels/DeviceArray.hpp"

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

/// History records (ContactState) as Width values per record, in Real.
template <std::uint32_t Width, class State>
std::vector<Real> flat_values(const std::vector<State>& host) {
  std::vector<Real> values;
  values.reserve(host.size() * Width);
  for (const State& s : host) values.insert(values.end(), s.value, s.value + Width);
  return values;
}

/// Host copy of a history array as Width values per record.
template <std::uint32_t Width, class State, class Space>
std::vector<Real> flat_values(const DeviceArray<State, Space>& states) {
  std::vector<State> host;
  states.download(host);
  return flat_values<Width>(host);
}

/// Width values per record as history records, rounded to the records' scalar.
template <std::uint32_t Width, class State>
std::vector<State> states_of(const std::vector<Real>& values) {
  std::vector<State> host(values.size() / Width);
  for (std::size_t k = 0; k < host.size(); ++k)
    for (std::uint32_t v = 0; v < Width; ++v) host[k].value[v] = values[k * Width + v];
  return host;
}

}  // namespace gpudem
