#pragma once
/// The choices of each contact-law slot (docs/architecture.md, "Contact law"), listed once, in the
/// order of their enum in core/ContactModel.hpp. Each choice carries its scene-file keyword, the
/// [[material]] and [[pair]] keys it reads (`material_keys`, space-separated) and its history
/// size, so the keyword → type mapping, the keys a law ignores and the history widths are read
/// from here: ContactModel.cpp takes the slots' names and keys, contact_history_width their
/// history sizes and ContactLawOf (ContactLaw.hpp) their types.
#include <cstddef>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "core/contact/CohesionLaws.hpp"
#include "core/contact/DampingLaws.hpp"
#include "core/contact/NormalLaws.hpp"
#include "core/contact/RollingLaws.hpp"
#include "core/contact/TangentialLaws.hpp"

namespace gpudem {

/// The choices of one slot, in enum order.
template <class... Slots>
struct SlotList {
  static constexpr std::size_t size = sizeof...(Slots);
  /// The choice of enum value `index`.
  template <std::size_t index>
  using At = std::tuple_element_t<index, std::tuple<Slots...>>;
  /// The enum value of choice Slot.
  template <class Slot>
  static constexpr std::size_t index_of() {
    constexpr bool is_slot[] = {std::is_same_v<Slot, Slots>...};
    std::size_t k = 0;
    while (!is_slot[k]) ++k;
    return k;
  }
  /// Scene-file keywords, in enum order.
  static std::vector<std::string> keywords() { return {Slots::keyword...}; }
  /// The material keys of each choice ("a b", space-separated), in enum order.
  static std::vector<std::string> material_keys() { return {Slots::material_keys...}; }
};

using NormalSlots = SlotList<HookeNormal, HertzNormal>;
using DampingSlots = SlotList<NoDamping, RestitutionDamping, ViscoelasticDamping>;
using TangentialSlots = SlotList<NoTangential, LinearHistoryTangential, MindlinTangential>;
using RollingSlots = SlotList<NoRolling, ConstantTorqueRolling, EpsdRolling>;
using CohesionSlots = SlotList<NoCohesion, SjkrCohesion, JkrCohesion>;

/// History values per contact of choice `index` of a slot that keeps history (tangential,
/// rolling, cohesion).
template <class... Slots>
constexpr int history_size_of(SlotList<Slots...>, std::size_t index) {
  constexpr int sizes[] = {Slots::history_size...};
  return sizes[index];
}

/// Calls visit(Slot{}) with the choice of enum value `index` (host dispatch on a scene's
/// choice, e.g. to its time-step limits).
template <class... Slots, class Visit>
void visit_slot(SlotList<Slots...>, std::size_t index, Visit&& visit) {
  std::size_t at = 0;
  ((at++ == index ? (visit(Slots{}), 0) : 0), ...);
}

}  // namespace gpudem
