// libFuzzer target: the scene parser on arbitrary bytes. Refusing input with kiri::InputError
// is the expected outcome; any other exception, a crash, a leak or undefined behaviour is a
// finding (ASan + UBSan are on in the fuzz build).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/scene/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const kiri::geometry::Scene scene = kiri::geometry::parse_scene(text, "fuzz.json", "/tmp");
        // What parses must write back to JSON that parses again.
        kiri::geometry::parse_scene(kiri::geometry::scene_to_json(scene), "again.json", "/tmp");
    } catch (const kiri::InputError&) {}
    return 0;
}
