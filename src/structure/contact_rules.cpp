#include "adjoin/structure/contact_rules.hpp"

#include <cmath>
#include <stdexcept>

namespace adjoin::structure {
namespace {

// The damping parameter's name for messages.
const char* damping_name(ContactModel model) {
  switch (model) {
    case ContactModel::linear: return "the damping ratio zeta, 0 <= zeta < 1";
    case ContactModel::hertzdamp: return "xi_bar >= 0";
    case ContactModel::jankowski: return "the damping ratio xi >= 0";
    default: return "";
  }
}

bool takes_stiffness(ContactModel m) { return m != ContactModel::none && m != ContactModel::impact; }
bool takes_restitution(ContactModel m) { return m != ContactModel::none && m != ContactModel::hertz; }
bool takes_damping(ContactModel m) {
  return m == ContactModel::linear || m == ContactModel::hertzdamp || m == ContactModel::jankowski;
}

}  // namespace

const std::vector<std::string>& contact_law_keys() {
  static const std::vector<std::string> keys = {"stiffness", "restitution", "damping", "tension_cut"};
  return keys;
}

std::vector<std::string> contact_keys_refused(ContactModel model) {
  std::vector<std::string> out;
  if (!takes_stiffness(model)) out.push_back("stiffness");
  if (!takes_restitution(model)) out.push_back("restitution");
  if (!takes_damping(model)) out.push_back("damping");
  if (model != ContactModel::linear) out.push_back("tension_cut");
  return out;
}

ContactLaw contact_law_from(const ContactTable& t, ContactModel model) {
  const auto fail = [&](const std::string& key, const std::string& message) {
    t.fail(key, message);
    throw std::logic_error("ContactTable::fail returned");  // it throws InputError
  };
  const std::string name = to_string(model);
  const std::string the_model = "the " + name + " model";
  ContactLaw law;
  law.model = model;

  // Keys the model does not take.
  if (model == ContactModel::none) {
    std::vector<std::string> with_law;  // the models but "none"
    for (const std::string& other : names<ContactModel>())
      if (other != to_string(ContactModel::none)) with_law.push_back(other);
    const std::string laws = join_names(with_law, "\"", ", ", " or ");
    for (const auto& key : contact_law_keys())
      if (t.has(key))
        fail(key, "a key of a contact law, but the contact has no model: set " + t.where + ".model = " + laws + " (or remove " + key + ")");
    return law;
  }
  if (model == ContactModel::impact) {
    if (t.has("stiffness"))
      fail("stiffness", "the impact model (Newton's law) has no stiffness: nothing penetrates; remove it, or choose a compliant "
                        "model (linear, hertz, hertzdamp, jankowski)");
    if (t.has("damping"))
      fail("damping", "the impact model (Newton's law) loses energy only through restitution (e); remove damping");
  }
  if (model == ContactModel::hertz)
    for (const char* key : {"restitution", "damping"})
      if (t.has(key))
        fail(key, "the hertz model is elastic (no damping, rebound ratio 1); remove " + std::string(key) +
                      ", or choose hertzdamp or jankowski for a damped Hertz contact");
  if (model != ContactModel::linear && t.has("tension_cut"))
    fail("tension_cut", "only the linear model pulls before separation (tension_cut cuts that); remove it from " + the_model);

  // Keys the model needs.
  if (takes_stiffness(model) && !t.has("stiffness"))
    fail("", "missing key stiffness: " + the_model + " needs its contact stiffness k (a positive number, " +
                 t.stiffness_unit(model) + ")");
  if (takes_damping(model)) {
    if (t.has("restitution") && t.has("damping"))
      fail("damping", "give restitution or damping, not both: damping (" + std::string(damping_name(model)) +
                          ") replaces the value " + the_model + " derives from restitution (e)");
    if (!t.has("restitution") && !t.has("damping"))
      fail("", "missing key restitution or damping: " + the_model + " takes its damping from the coefficient of restitution "
               "(restitution = e, 0 < e <= 1) or directly (damping = " + damping_name(model) + ")");
  }
  if (model == ContactModel::impact && !t.has("restitution"))
    fail("", "missing key restitution: the impact model (Newton's law) needs the coefficient of restitution e, 0 < e <= 1 "
             "(1: elastic, rebound at the approach speed)");

  // Values.
  if (t.has("stiffness")) {
    law.stiffness = t.number("stiffness");
    if (!(std::isfinite(law.stiffness) && law.stiffness > 0.0))
      fail("stiffness", "expected a positive contact stiffness (" + t.stiffness_unit(model) + ")");
  }
  if (t.has("restitution")) {
    law.restitution = t.number("restitution");
    if (!(std::isfinite(law.restitution) && law.restitution > 0.0 && law.restitution <= 1.0))
      fail("restitution", "expected a coefficient of restitution e with 0 < e <= 1 (1: elastic)");
  }
  if (t.has("damping")) {
    law.damping = t.number("damping");
    const bool ratio = model == ContactModel::linear;
    if (!(std::isfinite(law.damping) && law.damping >= 0.0 && (!ratio || law.damping < 1.0)))
      fail("damping", "expected " + std::string(damping_name(model)) + " (" + the_model + "'s damping parameter)");
  }
  if (t.has("tension_cut")) law.tension_cut = t.boolean("tension_cut");
  return law;
}

}  // namespace adjoin::structure
