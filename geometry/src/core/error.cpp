#include "kiri/geometry/core/error.hpp"

namespace kiri {
namespace {
std::string join_message(const std::string& file, const std::string& field, const std::string& reason)
{
    std::string out;
    for (const std::string* part : {&file, &field, &reason}) {
        if (part->empty())
            continue;
        if (!out.empty())
            out += ": ";
        out += *part;
    }
    return out;
}
}  // namespace

InputError::InputError(std::string file, std::string field, std::string reason)
    : Error(join_message(file, field, reason)), file_(std::move(file)), field_(std::move(field)),
      reason_(std::move(reason))
{}

}  // namespace kiri
