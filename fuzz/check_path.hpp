#pragma once
// What `rodlab check SCENE [--set ...]` does with a scene, for the fuzz targets: load and check
// it (rodlab::io::load_scene reads the file and hands its text to load_scene_from_string,
// which is called here directly), then compute the characteristics and render the report in
// text and JSON (apps/rodlab/cmd_check.cpp).
//
// The one expected outcome besides success is rodlab::io::SceneError: bad input, reported by
// the CLI with its file, line and field (exit 2). Any other exception is a finding (a bad input
// that the checks let through, or a bug), and so are crashes, sanitizer reports, aborts and
// time-outs: the target aborts, and libFuzzer keeps the input.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <span>
#include <string>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/rod/characteristics.hpp"

#include "check_report.hpp"
#include "report.hpp"

namespace rodlab::fuzz {

inline void check_like_the_cli(const std::string& text,
                               std::span<const io::Override> overrides) {
  try {
    const scene::Scene scene = io::load_scene_from_string(text, "fuzz.yaml", overrides);
    const int nodes = scene.solver.nodes;
    const auto tip = scene.tip_clamped() ? rod::TipSupport::clamped : rod::TipSupport::free;
    const rod::Characteristics c = rod::characteristics(scene.rod.to_model(), nodes, tip);
    const cli::Report report = cli::check_report(scene, c, "solver.nodes");
    (void)cli::render_text(report);
    (void)cli::render_json(report);
  } catch (const io::SceneError&) {
    // bad input, rejected as it should be
  } catch (const std::exception& e) {
    std::fprintf(stderr, "finding: an exception other than SceneError escaped: %s\n", e.what());
    std::abort();
  }
}

}  // namespace rodlab::fuzz
