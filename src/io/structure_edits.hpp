#pragma once
// Edits of a building scene's structure by dotted path (`--set building.A.period=0.8`,
// `--set link.1.slip_ratio=0.1`, `--unset link.2`), made on the parsed TOML tree so that the
// untouched keys keep their file lines in messages (internal to io).
//
// Paths: `building.A.KEY`, `building.A.damping.KEY`, `building.A.device.N.KEY`, `link.N.KEY`,
// `contact.N.KEY`, with N counted from 1 in the order of the scene's tables; `--unset` takes a
// key, a numbered table (`link.2`) or a whole section (`link`, `building.B`). Setting one of
// the alternatives `stiffness`, `stiffnesses`, `period` (or `mass`, `masses`; or a friction
// link's `slip_force`, `slip_ratio`) removes the others, as editing the file would; so do a
// contact's `restitution` and `damping`, and a contact's `model` removes the law keys that
// model does not take (structure/contact_rules.hpp), unless another --set put them there.
// Likewise a link's or device's `type` drops the keys the new type does not take
// (element_keys.hpp: a friction link made a dashpot loses slip_ratio and of). A --set of
// `link.N.KEY`, `contact.N.KEY` or `building.X.device.N.KEY` with N one more than the tables
// there are adds a table (a damper the base lacks); a larger N is an error saying which comes next.
#include <map>
#include <string>
#include <vector>

#include <toml++/toml.h>

namespace adjoin::detail {

// True if `key` (the part before '=' of a --set, or an --unset key) edits the structure.
bool is_structure_key(const std::string& key);

// Applies the unsets, then the overrides (only those whose key is a structure key) to `root`.
// `origins` receives, for each key an edit created, the reader's path of it
// ("link[1].slip_ratio") mapped to the option that created it ("--set link.1.slip_ratio=0.1"),
// for messages. InputError naming the option for a path that does not exist.
void edit_structure(toml::table& root, const std::vector<std::string>& overrides, const std::vector<std::string>& unsets,
                    std::map<std::string, std::string>& origins);

}  // namespace adjoin::detail
