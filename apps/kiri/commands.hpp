#pragma once
// Each subcommand of `kiri` registers itself on the app; its callback throws on failure and
// main turns any exception into one line on stderr and exit code 2.
#include <string>

#include <CLI/CLI.hpp>

#include "kiri/geometry/scene/scene_defaults.hpp"

namespace kiri::cli {

void add_info_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_author_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_new_command(CLI::App& app);

//! `kiri author INPUT -o OUT_DIR` with the default formats and limits (the outputs bench).
void run_author(const std::string& input, const std::string& out_dir);

//! Fails fast, before any expensive work, when `path` cannot be created: its folder must exist
//! and be writable. \throw kiri::IoError naming the path.
void check_output_file(const std::string& path);
//! The same for an output folder: an existing folder, or one whose nearest existing ancestor is
//! a writable folder. \throw kiri::IoError naming the path.
void check_output_folder(const std::string& path);

//! On stderr: the loader's warnings about the terrain (one line each) and, on one line, the keys
//! the pipeline derived from it ("kiri: derived: KEY VALUE (why); ...").
void print_derived(const geometry::DerivedDefaults& derived, const geometry::Heightfield& terrain);

}  // namespace kiri::cli
