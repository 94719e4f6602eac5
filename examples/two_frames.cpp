// The two-frame example (records/scenes/buildings/two-frames.toml) built in code instead of
// read from TOML: a 5-storey and a 3-storey frame with 5 % damping, Zener dampers in A's two
// lowest storeys, a friction link and a contact pair at floor 3, on the Northridge record.
// Prints what `adjoin run records/scenes/buildings/two-frames.toml` prints (without writing
// files), then a history kept as arrays.
//
//     two_frames [RECORD.AT2]     (default records/real/peer/RSN1044_DirRot2.AT2)
#include <adjoin/core/errors.hpp>
#include <adjoin/io/summary.hpp>
#include <adjoin/observe/channel_recorder.hpp>
#include <adjoin/structure/builder.hpp>
#include <adjoin/study/builder.hpp>
#include <adjoin/study/error_estimate.hpp>
#include <adjoin/study/run.hpp>
#include <cstdio>
#include <iostream>

int main(int argc, char** argv) {
  const char* record = argc > 1 ? argv[1] : "records/real/peer/RSN1044_DirRot2.AT2";
  try {
    adjoin::structure::StructureBuilder s;
    s.building('A', 5).mass(45.0e3).stiffness(5.482e6).modal_damping(0.05)
        .zener({1, 2}, {.k = 1.0e6, .order = 0.5, .tau_x = 0.2, .tau_f = 0.01});
    s.building('B', 3).masses({60.0e3, 60.0e3, 50.0e3}).period(0.5).rayleigh_damping(0.05, 1, 2);
    s.friction_link_ratio(3, 3, 0.05, 'B');  // slip force: 5 % of B's weight
    s.contact(3, 3, 0.05);                    // a 5 cm gap, no contact law
    adjoin::BuildingRunOptions options;
    options.name = "two-frames";
    options.h = 0.002;   // s
    options.t_end = 45.0;  // s: the record (40 s) and some free vibration
    const adjoin::RunSpec spec = adjoin::building_run_spec(s.build(), adjoin::record_ground(record), options);

    adjoin::ChannelRecorder recorder({"A.x5", "link1.force"});
    const adjoin::Report report = adjoin::run(spec, {&recorder});
    const adjoin::ErrorEstimate estimate = adjoin::estimate_error(spec, report);  // as `adjoin run` does
    std::cout << adjoin::brief_report(spec, report, &estimate);
    std::printf("recorded %zu rows of %zu channels; A.x5 at t = %.1f s: %+.5f m\n", static_cast<std::size_t>(recorder.times().size()),
                recorder.names().size(), recorder.times()[5000], recorder.values()(5000, 0));
    return 0;
  } catch (const adjoin::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return adjoin::kExitInputError;
  } catch (const adjoin::NumericalError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return adjoin::kExitNumericalError;
  }
}
