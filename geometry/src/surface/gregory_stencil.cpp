#include <stdexcept>

#include "surface/face_stencil.hpp"

namespace kiri::geometry {

std::unique_ptr<FaceStencils> make_gregory_stencils(const PolyMesh&)
{
    throw std::runtime_error("gregory stencils: not implemented yet");
}

}  // namespace kiri::geometry
