#pragma once
// The keys of a contact law (SPEC §6): a building scene's [[contact]], a two-block scene's
// [model.contact] and the typed builder's contacts (structure/builder.hpp) take the same
// `model`, `stiffness`, `restitution`, `damping` and `tension_cut`, with the same rules:
//
//   model        "none" (the default), "linear", "hertz", "hertzdamp", "jankowski", "impact"
//   stiffness    needed by linear, hertz, hertzdamp, jankowski; refused by impact
//   restitution  e, 0 < e <= 1: linear, hertzdamp, jankowski need it or damping (one of the two);
//                impact needs it; hertz refuses it
//   damping      the model's damping parameter given directly (zeta < 1 for linear, xi_bar for
//                hertzdamp, xi for jankowski), >= 0; refused by hertz and impact
//   tension_cut  true or false, linear only
//   model none refuses all four.
#include <functional>
#include <string>
#include <vector>

#include "adjoin/structure/contact.hpp"

namespace adjoin::structure {

// How a table (a scene's, or the builder's values) is read: `has` a key, its `number` (the caller checks the type), its `boolean`,
// and `fail`, which throws InputError naming the key ("" for the table itself) with the
// message. `where` names the table in messages ("contact[2]", "model.contact");
// `stiffness_unit` says in what unit a model's stiffness is given.
struct ContactTable {
  std::string where;
  std::function<bool(const std::string&)> has;
  std::function<double(const std::string&)> number;
  std::function<bool(const std::string&)> boolean;
  std::function<void(const std::string& key, const std::string& message)> fail;
  std::function<std::string(ContactModel)> stiffness_unit;
};

// The law the table gives for `model` (already read), every rule above checked; the stiffness
// as given (the caller scales it). The restitution stays 1 when not given.
ContactLaw contact_law_from(const ContactTable& t, ContactModel model);

// The law keys `model` refuses: what an edit that sets the model drops from the table, as
// editing the file would ("restitution", "damping" for hertz).
std::vector<std::string> contact_keys_refused(ContactModel model);

// The law keys, without `model`.
const std::vector<std::string>& contact_law_keys();

}  // namespace adjoin::structure
