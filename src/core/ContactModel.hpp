#pragma once
/// Which contact law a scene uses: one choice per slot (docs/architecture.md, "Contact law"). The
/// engine instantiates one force compute per valid combination; this header is the host-side
/// list of those combinations, shared by the scene loader and the engine factory. Each enum
/// lists its slot's choices in the order of their SlotList (core/contact/ContactSlots.hpp),
/// which gives their names and history sizes.
#include <cstdint>
#include <string>
#include <vector>

#include "core/CompiledContactLaws.hpp"
#include "core/contact/ContactSlots.hpp"

namespace gpudem {

enum class NormalLaw : std::uint8_t { Hooke, Hertz };
enum class DampingLaw : std::uint8_t { None, Restitution, Viscoelastic };
enum class TangentialLaw : std::uint8_t { None, LinearHistory, Mindlin };
enum class RollingLaw : std::uint8_t { None, ConstantTorque, Epsd };
enum class CohesionLaw : std::uint8_t { None, Sjkr, Jkr };

struct ContactModel {
  NormalLaw normal = NormalLaw::Hooke;
  DampingLaw damping = DampingLaw::Restitution;
  TangentialLaw tangential = TangentialLaw::LinearHistory;
  RollingLaw rolling = RollingLaw::None;
  CohesionLaw cohesion = CohesionLaw::None;

  friend constexpr bool operator==(const ContactModel& a, const ContactModel& b) {
    return a.normal == b.normal && a.damping == b.damping && a.tangential == b.tangential &&
           a.rolling == b.rolling && a.cohesion == b.cohesion;
  }
  friend bool operator!=(const ContactModel& a, const ContactModel& b) { return !(a == b); }
};

/// Scene-file names of each slot's choices, in enum order (their SlotList's keywords).
const std::vector<std::string>& normal_law_names();
const std::vector<std::string>& damping_law_names();
const std::vector<std::string>& tangential_law_names();
const std::vector<std::string>& rolling_law_names();
const std::vector<std::string>& cohesion_law_names();

/// "normal/damping/tangential/rolling/cohesion", e.g. "hertz/restitution/mindlin/none/none".
std::string contact_model_name(const ContactModel& model);

/// The combinations the engine is built for: hooke pairs with damping none|restitution,
/// tangential none|linear_history and cohesion none|sjkr; hertz with damping
/// none|restitution|viscoelastic, tangential none|mindlin and cohesion none|sjkr|jkr (JKR is a
/// Hertz theory); rolling is free with either.
constexpr bool is_valid_contact_model(const ContactModel& m) {
  return m.normal == NormalLaw::Hooke
             ? m.damping != DampingLaw::Viscoelastic && m.tangential != TangentialLaw::Mindlin &&
                   m.cohesion != CohesionLaw::Jkr
             : m.tangential != TangentialLaw::LinearHistory;
}
std::vector<ContactModel> valid_contact_models();

/// A set of contact models: one choice per slot (normal, damping, tangential, rolling,
/// cohesion) as its enum value, or -1 for any.
struct ContactModelPattern {
  int slot[5];
  constexpr bool matches(const ContactModel& m) const {
    const int value[5] = {static_cast<int>(m.normal), static_cast<int>(m.damping),
                          static_cast<int>(m.tangential), static_cast<int>(m.rolling),
                          static_cast<int>(m.cohesion)};
    for (int k = 0; k < 5; ++k)
      if (slot[k] >= 0 && slot[k] != value[k]) return false;
    return true;
  }
};

/// The patterns of the build option GPUDEM_CONTACT_LAWS (all valid laws by default).
inline constexpr ContactModelPattern kCompiledContactLaws[] = {GPUDEM_CONTACT_LAW_PATTERNS};

/// True for the valid laws this build compiles a force compute for (GPUDEM_CONTACT_LAWS).
constexpr bool is_compiled_contact_model(const ContactModel& m) {
  if (!is_valid_contact_model(m)) return false;
  for (const ContactModelPattern& pattern : kCompiledContactLaws)
    if (pattern.matches(m)) return true;
  return false;
}

/// The laws this build compiles, for error messages: "every valid law" or
/// "GPUDEM_CONTACT_LAWS=<patterns>: <laws>".
std::string compiled_contact_models_text();

/// History values per contact that the law keeps (ContactLaw::history_size, docs/architecture.md,
/// "Contact law"): its tangential, rolling and cohesion slots' history sizes.
constexpr std::uint32_t contact_history_width(const ContactModel& m) {
  return static_cast<std::uint32_t>(
      history_size_of(TangentialSlots{}, static_cast<std::size_t>(m.tangential)) +
      history_size_of(RollingSlots{}, static_cast<std::size_t>(m.rolling)) +
      history_size_of(CohesionSlots{}, static_cast<std::size_t>(m.cohesion)));
}

/// A [[material]] or [[pair]] key that a contact law does not read, though another choice of
/// one of its slots would: a value given for it is ignored.
struct IgnoredLawKey {
  std::string key;
  std::string slot;     ///< "cohesion"
  std::string chosen;   ///< the law's choice for the slot, "none"
  std::string readers;  ///< the choices that read it, "sjkr" or "linear_history|mindlin"
};

/// The keys `model` ignores (each slot's choices' material_keys that its own choice lacks).
std::vector<IgnoredLawKey> ignored_law_keys(const ContactModel& model);

/// valid_contact_models() in a few words, for error messages: "hooke: damping
/// none|restitution, tangential none|linear_history, cohesion none|sjkr; hertz: ...; rolling
/// none|...|epsd with either".
std::string valid_contact_models_text();

}  // namespace gpudem
