#pragma once
// Every enum <-> string pair in one table (SPEC §4 core/). Each named enum has one table below
// (EnumTable<E>, constexpr: to_string costs a few compares): per value its name (what to_string gives, what files and messages
// spell) and any other spellings a reader accepts (aliases); names<E>() lists the names in the
// order messages list them.
//
//     to_string(LinkType::friction)              -> "friction"
//     parse_enum("hertz", &model)                -> true, model = ContactModel::hertz
//     names<Scheme>()                            -> {"implicit", "implicit-damped", ...}
//
// The enums a higher layer uses (structure/, ground/, solver/) are declared here, as plain
// enums in their own namespaces, so that core can hold their tables (core is the lowest layer:
// scripts/check_layers.py); their old headers include this one. A new named enum: its
// declaration and its EnumTable here.
#include <string>
#include <string_view>
#include <vector>

namespace adjoin {

// ---- the enums ----

// Which engine sums a fractional element's history (fractional/history.hpp).
enum class HistoryEngine { direct, fft, soe };

// The two-block scenes' time-stepping schemes (solver/options.hpp).
enum class Scheme {
  // The paper's algorithm (3.1)/(3.2): explicit central differences, Grünwald–Letnikov
  // history, stick/slip switching on the grid. First order, conditionally stable. The
  // regression baseline.
  paper,
  // The robust default: trapezoidal (Newmark average acceleration) mechanics at velocity
  // level, rods implicit through their current convolution weight, second-order convolution
  // quadrature (BDF2) for the fractional terms, and the damper resolved each step as a relay
  // problem in closed form (stick holds exactly, no chatter, no regularisation). Second
  // order away from switching instants, stable for any h.
  implicit,
  // The same with first-order Grünwald–Letnikov weights for the rods.
  implicit_gl,
  // "implicit" with a backward-Euler step after every switch, which damps the stiff modes a
  // switch excites (the default scheme does this only when the stiffest mode is unresolved by
  // the step). Second order; error constants near switches about ten times larger.
  implicit_damped,
};

// A friction link's phase (structure/state.hpp).
enum class Phase { stick, slip_right, slip_left };

// Units of a record's acceleration values (ground/record.hpp).
enum class AccelUnit { g, m_s2, cm_s2, mm_s2 };

// Filtered noise (ground/synthesis.hpp): the ground filter and the envelope.
enum class SpectrumModel { kanai_tajimi, clough_penzien };
enum class EnvelopeKind { none, jennings_housner_tsai, saragoni_hart };

// A record's Butterworth filter (ground/processing.hpp: ButterworthFilter::Type).
enum class FilterType { lowpass, highpass, bandpass };

// Response spectra (post/): the periods' spacing, the inelastic oscillator's hysteresis, how
// a suite is scaled to a target.
enum class PeriodSpacing { linear, log };
enum class Hysteresis { elastic_perfectly_plastic, bilinear };
enum class SuiteScaling { fit, uniform };

namespace structure {
// A contact pair's law (structure/contact.hpp).
enum class ContactModel { none, linear, hertz, hertzdamp, jankowski, impact };
// The storey device kinds (structure/device_kinds.hpp), one row each: the value and the name
// a scene spells. Each kind's keys, checks and model are its own file,
// src/structure/devices/<value>.cpp: a new kind is that file and one row here.
#define ADJOIN_DEVICE_KINDS(ROW) \
  ROW(spring, "spring")          \
  ROW(dashpot, "dashpot")        \
  ROW(zener, "zener")            \
  ROW(bilinear, "bilinear")      \
  ROW(bouc_wen, "bouc-wen")      \
  ROW(kelvin, "kelvin")          \
  /* a new kind: its row above this line */
#define ADJOIN_DEVICE_VALUE(value, name) value,
enum class DeviceType { ADJOIN_DEVICE_KINDS(ADJOIN_DEVICE_VALUE) };
#undef ADJOIN_DEVICE_VALUE
// A building's inherent damping, a link (structure/building.hpp).
// A storey spring's own law (SPEC §7; structure/building.hpp).
enum class HysteresisModel { elastic, bilinear, bouc_wen };
// An isolated base's bearing (SPEC §7; structure/building.hpp).
enum class BaseModel { flat_slider, friction_pendulum };
enum class DampingModel { none, modal, rayleigh };
// The link kinds (structure/link_kinds.hpp), one row each, as the devices': each kind's keys,
// checks and model are its own file, src/structure/links/<value>.cpp.
#define ADJOIN_LINK_KINDS(ROW) \
  ROW(friction, "friction")    \
  ROW(dashpot, "dashpot")      \
  ROW(spring, "spring")        \
  ROW(zener, "zener")          \
  ROW(kelvin, "kelvin")        \
  /* a new kind: its row above this line */
#define ADJOIN_LINK_VALUE(value, name) value,
enum class LinkType { ADJOIN_LINK_KINDS(ADJOIN_LINK_VALUE) };
#undef ADJOIN_LINK_VALUE
}  // namespace structure

// ---- the tables ----

template <class E>
struct EnumName {
  E value;
  const char* name;
};

// EnumTable<E>::entries: each value's name first (in the order messages list the accepted
// names), then the aliases a reader also accepts. Specialised below for each named enum.
template <class E>
struct EnumTable;

template <class E>
concept NamedEnum = requires { EnumTable<E>::entries; };

template <>
struct EnumTable<HistoryEngine> {
  static constexpr EnumName<HistoryEngine> entries[] = {{HistoryEngine::direct, "direct"}, {HistoryEngine::fft, "fft"}, {HistoryEngine::soe, "soe"}};
};

template <>
struct EnumTable<Scheme> {
  static constexpr EnumName<Scheme> entries[] = {{Scheme::implicit, "implicit"},
                                                 {Scheme::implicit_damped, "implicit-damped"},
                                                 {Scheme::implicit_gl, "implicit-gl"},
                                                 {Scheme::paper, "paper"}};
};

template <>
struct EnumTable<Phase> {
  static constexpr EnumName<Phase> entries[] = {
      {Phase::stick, "stick"}, {Phase::slip_right, "slip_right"}, {Phase::slip_left, "slip_left"}};
};

// (Spelled as parse_accel_unit leaves a unit: lower case, no blanks, "s2" for every form of s^2.)
template <>
struct EnumTable<AccelUnit> {
  static constexpr EnumName<AccelUnit> entries[] = {
      {AccelUnit::g, "g"}, {AccelUnit::m_s2, "m/s2"}, {AccelUnit::cm_s2, "cm/s2"}, {AccelUnit::mm_s2, "mm/s2"}, {AccelUnit::cm_s2, "gal"}};
};

// (Spelled as the filtered-noise readers leave a name: lower case, '-' for '_'.)
template <>
struct EnumTable<SpectrumModel> {
  static constexpr EnumName<SpectrumModel> entries[] = {{SpectrumModel::kanai_tajimi, "kanai-tajimi"},
                                                        {SpectrumModel::clough_penzien, "clough-penzien"},
                                                        {SpectrumModel::kanai_tajimi, "kt"},
                                                        {SpectrumModel::clough_penzien, "cp"}};
};

template <>
struct EnumTable<EnvelopeKind> {
  static constexpr EnumName<EnvelopeKind> entries[] = {{EnvelopeKind::none, "none"},
                                                       {EnvelopeKind::jennings_housner_tsai, "jennings-housner-tsai"},
                                                       {EnvelopeKind::saragoni_hart, "saragoni-hart"},
                                                       {EnvelopeKind::jennings_housner_tsai, "jht"},
                                                       {EnvelopeKind::saragoni_hart, "sh"}};
};

template <>
struct EnumTable<FilterType> {
  static constexpr EnumName<FilterType> entries[] = {
      {FilterType::bandpass, "bandpass"}, {FilterType::highpass, "highpass"}, {FilterType::lowpass, "lowpass"}};
};

template <>
struct EnumTable<PeriodSpacing> {
  static constexpr EnumName<PeriodSpacing> entries[] = {
      {PeriodSpacing::log, "log"}, {PeriodSpacing::linear, "lin"}, {PeriodSpacing::linear, "linear"}};
};

template <>
struct EnumTable<Hysteresis> {
  static constexpr EnumName<Hysteresis> entries[] = {{Hysteresis::elastic_perfectly_plastic, "epp"}, {Hysteresis::bilinear, "bilinear"}};
};

template <>
struct EnumTable<SuiteScaling> {
  static constexpr EnumName<SuiteScaling> entries[] = {{SuiteScaling::fit, "fit"}, {SuiteScaling::uniform, "uniform"}};
};

template <>
struct EnumTable<structure::ContactModel> {
  using E = structure::ContactModel;
  static constexpr EnumName<E> entries[] = {{E::none, "none"},           {E::linear, "linear"}, {E::hertz, "hertz"},
                                            {E::hertzdamp, "hertzdamp"}, {E::jankowski, "jankowski"}, {E::impact, "impact"}};
};

template <>
struct EnumTable<structure::DeviceType> {
  using E = structure::DeviceType;
#define ADJOIN_DEVICE_NAME(value, name) {E::value, name},
  static constexpr EnumName<E> entries[] = {ADJOIN_DEVICE_KINDS(ADJOIN_DEVICE_NAME)};
#undef ADJOIN_DEVICE_NAME
};

template <>
struct EnumTable<structure::HysteresisModel> {
  using E = structure::HysteresisModel;
  static constexpr EnumName<E> entries[] = {{E::elastic, "elastic"}, {E::bilinear, "bilinear"}, {E::bouc_wen, "bouc-wen"}};
};

template <>
struct EnumTable<structure::BaseModel> {
  using E = structure::BaseModel;
  static constexpr EnumName<E> entries[] = {{E::flat_slider, "flat-slider"}, {E::friction_pendulum, "friction-pendulum"}};
};

template <>
struct EnumTable<structure::DampingModel> {
  using E = structure::DampingModel;
  static constexpr EnumName<E> entries[] = {{E::none, "none"}, {E::modal, "modal"}, {E::rayleigh, "rayleigh"}};
};

template <>
struct EnumTable<structure::LinkType> {
  using E = structure::LinkType;
#define ADJOIN_LINK_NAME(value, name) {E::value, name},
  static constexpr EnumName<E> entries[] = {ADJOIN_LINK_KINDS(ADJOIN_LINK_NAME)};
#undef ADJOIN_LINK_NAME
};

// ---- the functions ----

// The value's name ("?" for a value outside the table), as a C string (for printf-style
// writers) and as a std::string.
template <NamedEnum E>
const char* enum_name(E value) {
  for (const auto& entry : EnumTable<E>::entries)
    if (entry.value == value) return entry.name;
  return "?";
}
template <NamedEnum E>
std::string to_string(E value) {
  return enum_name(value);
}
// A phase's and a contact model's names have always been C strings (the writers print them
// with %s): these overloads, preferred to the template, keep them so.
inline const char* to_string(Phase phase) { return enum_name(phase); }

// The value named `text` (a name or an alias, exactly as spelled); false if none.
template <NamedEnum E>
bool parse_enum(std::string_view text, E* value) {
  for (const auto& entry : EnumTable<E>::entries)
    if (text == entry.name) {
      if (value) *value = entry.value;
      return true;
    }
  return false;
}

// The names (not the aliases), in the table's order: what a message lists as accepted.
template <NamedEnum E>
std::vector<std::string> names() {
  std::vector<std::string> out;
  for (const auto& entry : EnumTable<E>::entries) {
    bool seen = false;
    for (const auto& name : out) seen = seen || name == enum_name(entry.value);
    if (!seen) out.push_back(enum_name(entry.value));
  }
  return out;
}

// A list of names for a message: join_names(names<E>(), "\"", ", ", " or ") gives
// "a", "b" or "c".
std::string join_names(const std::vector<std::string>& list, const char* quote, const char* separator, const char* last);

namespace structure {
using adjoin::enum_name;
using adjoin::names;
using adjoin::parse_enum;
using adjoin::to_string;
inline const char* to_string(ContactModel model) { return enum_name(model); }
}  // namespace structure

}  // namespace adjoin
