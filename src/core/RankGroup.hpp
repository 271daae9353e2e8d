#pragma once
/// The ranks of a run and the one vocabulary of collective operations among them
/// (docs/architecture.md, "Ranks"): element-wise reductions, broadcast, gather, all-to-all
/// exchange of byte buffers and the agreement on the first failure. Every call is collective:
/// all ranks of the group make it at the same point. comm/MpiRankGroup implements it over MPI,
/// SingleRank for a run on one rank; no code outside src/comm sees MPI.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/InputError.hpp"

namespace gpudem {

/// Bytes for or from each rank, indexed by rank.
using RankBuffers = std::vector<std::vector<char>>;

enum class Reduction { Sum, Max, Min };

class RankGroup {
 public:
  virtual ~RankGroup() = default;

  virtual int rank() const = 0;
  virtual int size() const = 0;
  bool is_root() const { return rank() == 0; }

  /// values[k] becomes the reduction over ranks of every rank's values[k] (n the same on all
  /// ranks); an unsigned sum wraps modulo 2^64 (checksums).
  virtual void reduce(Reduction op, double* values, std::size_t n) const = 0;
  virtual void reduce(Reduction op, std::uint64_t* values, std::size_t n) const = 0;
  /// `bytes` of rank `root` on every rank (resized).
  virtual void broadcast(std::vector<char>& bytes, int root) const = 0;
  /// Every rank's `mine` on every rank, indexed by rank.
  virtual void all_gather(const std::vector<char>& mine, RankBuffers& all) const = 0;
  /// Sends outgoing[q] to each rank q (size() entries; empty ones send nothing) and returns in
  /// incoming[q] what rank q sent here.
  virtual void exchange(const RankBuffers& outgoing, RankBuffers& incoming) const = 0;

  template <class T>
  T sum(T value) const {
    reduce(Reduction::Sum, &value, 1);
    return value;
  }
  template <class T>
  T max(T value) const {
    reduce(Reduction::Max, &value, 1);
    return value;
  }
  template <class T>
  T min(T value) const {
    reduce(Reduction::Min, &value, 1);
    return value;
  }
  template <class T>
  void sum(std::vector<T>& values) const {
    if (!values.empty()) reduce(Reduction::Sum, values.data(), values.size());
  }
  template <class T>
  void max(std::vector<T>& values) const {
    if (!values.empty()) reduce(Reduction::Max, values.data(), values.size());
  }

  /// The lowest rank for which `flag` is true; size() when none.
  int first_rank_with(bool flag) const {
    const std::uint64_t after_me = flag ? static_cast<std::uint64_t>(size() - rank()) : 0;
    return size() - static_cast<int>(max(after_me));
  }

  /// Every rank's `mine` concatenated in rank order, on every rank (T holds plain values).
  template <class T>
  std::vector<T> gather(const std::vector<T>& mine) const {
    static_assert(std::is_trivially_copyable_v<T>, "gather moves plain values");
    std::vector<char> bytes(mine.size() * sizeof(T));
    if (!bytes.empty()) std::memcpy(bytes.data(), mine.data(), bytes.size());
    RankBuffers all;
    all_gather(bytes, all);
    std::vector<T> out;
    for (const std::vector<char>& part : all) {
      const std::size_t at = out.size();
      out.resize(at + part.size() / sizeof(T));
      if (!part.empty()) std::memcpy(out.data() + at, part.data(), part.size());
    }
    return out;
  }

  /// `value` of rank `root` on every rank.
  template <class T>
  T broadcast_value(T value, int root) const {
    static_assert(std::is_trivially_copyable_v<T>, "broadcast_value moves a plain value");
    std::vector<char> bytes(sizeof(T));
    std::memcpy(bytes.data(), &value, sizeof(T));
    broadcast(bytes, root);
    std::memcpy(&value, bytes.data(), sizeof(T));
    return value;
  }

  /// Σ of `count` over the ranks before this one (0 on rank 0): the first global index of
  /// this rank's part when the parts hold consecutive indices in rank order.
  std::uint64_t sum_before(std::uint64_t count) const {
    const std::vector<std::uint64_t> counts = gather(std::vector<std::uint64_t>{count});
    std::uint64_t before = 0;
    for (int q = 0; q < rank(); ++q) before += counts[q];
    return before;
  }
};

/// A run on one rank: every collective returns its input.
class SingleRank final : public RankGroup {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  void reduce(Reduction, double*, std::size_t) const override {}
  void reduce(Reduction, std::uint64_t*, std::size_t) const override {}
  void broadcast(std::vector<char>&, int) const override {}
  void all_gather(const std::vector<char>& mine, RankBuffers& all) const override { all = {mine}; }
  void exchange(const RankBuffers& outgoing, RankBuffers& incoming) const override {
    incoming = outgoing;
  }
};

/// A failure of one rank, to be thrown on every rank.
struct RankFailure {
  std::string message;  ///< empty: no failure
  bool input = false;   ///< an InputError (exit 2), else a std::runtime_error (exit 1)
};

/// The message of the lowest rank whose `message` is not empty, on every rank; none when every
/// rank's is empty.
inline std::optional<std::string> first_message(const RankGroup& group,
                                                const std::string& message) {
  const int first = group.first_rank_with(!message.empty());
  if (first == group.size()) return std::nullopt;
  std::vector<char> text(message.begin(), message.end());
  group.broadcast(text, first);
  return std::string(text.begin(), text.end());
}

/// Throws the failure of the lowest rank that has one on every rank: InputError(message) or
/// std::runtime_error(message); returns when no rank has one.
inline void throw_first_failure(const RankGroup& group, const RankFailure& failure) {
  // The kind travels as the message's first character, so one agreement carries both.
  const std::string mine =
      failure.message.empty() ? "" : (failure.input ? "I" : "R") + failure.message;
  const std::optional<std::string> first = first_message(group, mine);
  if (!first) return;
  if ((*first)[0] == 'I') throw InputError("", 0, "", first->substr(1));
  throw std::runtime_error(first->substr(1));
}

/// What `attempt()` returns, when it throws on no rank; else every rank throws the lowest
/// failing rank's error (an InputError as such, any other std::exception as a
/// std::runtime_error with its message), so that rank 0 reports it and no rank is left waiting
/// in a collective.
template <class Attempt>
auto agree_on_failure(const RankGroup& group, Attempt&& attempt) -> decltype(attempt()) {
  std::optional<decltype(attempt())> result;
  RankFailure failure;
  try {
    result.emplace(attempt());
  } catch (const InputError& e) {
    failure = {e.what(), true};
  } catch (const std::exception& e) {
    failure = {e.what(), false};
  }
  throw_first_failure(group, failure);
  return std::move(*result);
}

}  // namespace gpudem
