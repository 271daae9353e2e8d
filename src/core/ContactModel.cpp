#include "core/ContactModel.hpp"

#include <algorithm>
#include <set>

namespace gpudem {

namespace {

/// "a|b" of the names whose enum value is in `used`, in enum order.
std::string alternatives(const std::vector<std::string>& names, const std::set<int>& used) {
  std::string text;
  for (int value : used) text += (text.empty() ? "" : "|") + names[value];
  return text;
}

/// The damping, tangential and cohesion choices that go with `normal`, as "damping a|b,
/// tangential c|d, cohesion e|f".
std::string choices_with(NormalLaw normal) {
  std::set<int> damping, tangential, cohesion;
  for (const ContactModel& m : valid_contact_models()) {
    if (m.normal != normal) continue;
    damping.insert(static_cast<int>(m.damping));
    tangential.insert(static_cast<int>(m.tangential));
    cohesion.insert(static_cast<int>(m.cohesion));
  }
  return "damping " + alternatives(damping_law_names(), damping) + ", tangential " +
         alternatives(tangential_law_names(), tangential) + ", cohesion " +
         alternatives(cohesion_law_names(), cohesion);
}

}  // namespace

const std::vector<std::string>& normal_law_names() {
  static const std::vector<std::string> names = NormalSlots::keywords();
  return names;
}
const std::vector<std::string>& damping_law_names() {
  static const std::vector<std::string> names = DampingSlots::keywords();
  return names;
}
const std::vector<std::string>& tangential_law_names() {
  static const std::vector<std::string> names = TangentialSlots::keywords();
  return names;
}
const std::vector<std::string>& rolling_law_names() {
  static const std::vector<std::string> names = RollingSlots::keywords();
  return names;
}
const std::vector<std::string>& cohesion_law_names() {
  static const std::vector<std::string> names = CohesionSlots::keywords();
  return names;
}

std::string contact_model_name(const ContactModel& m) {
  return normal_law_names()[static_cast<int>(m.normal)] + "/" +
         damping_law_names()[static_cast<int>(m.damping)] + "/" +
         tangential_law_names()[static_cast<int>(m.tangential)] + "/" +
         rolling_law_names()[static_cast<int>(m.rolling)] + "/" +
         cohesion_law_names()[static_cast<int>(m.cohesion)];
}

std::vector<ContactModel> valid_contact_models() {
  std::vector<ContactModel> models;
  for (std::size_t n = 0; n < NormalSlots::size; ++n)
    for (std::size_t d = 0; d < DampingSlots::size; ++d)
      for (std::size_t t = 0; t < TangentialSlots::size; ++t)
        for (std::size_t r = 0; r < RollingSlots::size; ++r)
          for (std::size_t c = 0; c < CohesionSlots::size; ++c) {
            const ContactModel m{static_cast<NormalLaw>(n), static_cast<DampingLaw>(d),
                                 static_cast<TangentialLaw>(t), static_cast<RollingLaw>(r),
                                 static_cast<CohesionLaw>(c)};
            if (is_valid_contact_model(m)) models.push_back(m);
          }
  return models;
}

std::string compiled_contact_models_text() {
  std::string text;
  std::size_t compiled = 0;
  for (const ContactModel& m : valid_contact_models()) {
    if (!is_compiled_contact_model(m)) continue;
    text += (compiled++ == 0 ? "" : ", ") + contact_model_name(m);
  }
  if (compiled == valid_contact_models().size()) return "every valid law";
  return std::string("GPUDEM_CONTACT_LAWS=") + GPUDEM_CONTACT_LAWS_OPTION + ": " +
         (compiled == 0 ? "none" : text);
}

namespace {

/// The space-separated words of `text`.
std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find(' ', at), text.size());
    if (end > at) out.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  return out;
}

/// The keys of one slot's other choices that its choice `chosen` does not read.
void add_ignored_keys(const char* slot, const std::vector<std::string>& names,
                      const std::vector<std::string>& keys, std::size_t chosen,
                      std::vector<IgnoredLawKey>& out) {
  const std::vector<std::string> read = words(keys[chosen]);
  for (std::size_t c = 0; c < keys.size(); ++c)
    for (const std::string& key : words(keys[c])) {
      if (std::find(read.begin(), read.end(), key) != read.end()) continue;
      auto known = std::find_if(out.begin(), out.end(),
                                [&](const IgnoredLawKey& k) { return k.key == key; });
      if (known == out.end())
        out.push_back({key, slot, names[chosen], names[c]});
      else
        known->readers += "|" + names[c];
    }
}

}  // namespace

std::vector<IgnoredLawKey> ignored_law_keys(const ContactModel& m) {
  std::vector<IgnoredLawKey> out;
  add_ignored_keys("damping", damping_law_names(), DampingSlots::material_keys(),
                   static_cast<std::size_t>(m.damping), out);
  add_ignored_keys("tangential", tangential_law_names(), TangentialSlots::material_keys(),
                   static_cast<std::size_t>(m.tangential), out);
  add_ignored_keys("rolling", rolling_law_names(), RollingSlots::material_keys(),
                   static_cast<std::size_t>(m.rolling), out);
  add_ignored_keys("cohesion", cohesion_law_names(), CohesionSlots::material_keys(),
                   static_cast<std::size_t>(m.cohesion), out);
  return out;
}

std::string valid_contact_models_text() {
  std::set<int> rolling;
  for (const ContactModel& m : valid_contact_models()) rolling.insert(static_cast<int>(m.rolling));
  std::string text;
  for (std::size_t n = 0; n < normal_law_names().size(); ++n) {
    text += normal_law_names()[n] + ": " + choices_with(static_cast<NormalLaw>(n)) + "; ";
  }
  return text + "rolling " + alternatives(rolling_law_names(), rolling) + " with either";
}

}  // namespace gpudem
