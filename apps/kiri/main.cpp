// kiri: the command-line tool. Exit codes: 0 success, 2 any error (bad input, bad usage,
// failure to write), with exactly one line on stderr.
#include <cstdio>
#include <exception>
#include <new>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "kiri/geometry/core/error.hpp"

int main(int argc, char** argv)
{
    CLI::App app{"kiri: fog clouds that follow real terrain"};
    app.set_version_flag("--version", "kiri 0.1.0");
    app.require_subcommand(1);
    kiri::cli::add_info_command(app);
    kiri::cli::add_new_command(app);
    kiri::cli::add_render_command(app);
    kiri::cli::add_author_command(app);
    kiri::cli::add_bench_command(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "kiri: %s (see kiri --help)\n", e.what());
        return 2;
    } catch (const kiri::Error& e) {
        std::fprintf(stderr, "kiri: %s\n", e.what());
        return 2;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "kiri: out of memory (try a smaller terrain, fewer layers or particles)\n");
        return 2;
    } catch (const std::exception&) {
        // A library's own message (std::, allocator or assertion text) means nothing to a user.
        std::fprintf(stderr, "kiri: an internal error stopped kiri on this input (please report it with the input)\n");
        return 2;
    }
    return 0;
}
