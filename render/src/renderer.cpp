#include "kiri/render/renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <tuple>

#include <glm/gtc/matrix_inverse.hpp>

#include "flip_rows.hpp"
#include "frame_context.hpp"
#include "froxel_pass.hpp"
#include "gl_debug.hpp"
#include "kiri/geometry/volume/froxel_options.hpp"
#include "kiri/geometry/medium/fog_partition.hpp"
#include "kiri/geometry/terrain/terrain.hpp"
#include "layers_pass.hpp"
#include "overlay_pass.hpp"
#include "particles_pass.hpp"
#include "pass_timer.hpp"
#include "render_origin.hpp"
#include "render_targets.hpp"
#include "shadow_map_pass.hpp"
#include "sky_pass.hpp"
#include "sun_volume.hpp"
#include "light_volume_texture.hpp"
#include "terrain_pass.hpp"
#include "tonemap_pass.hpp"

namespace kiri::render {

using detail::FrameContext;

using detail::PassTimer;
using detail::ScopedPassTimer;

struct Renderer::Impl {
    detail::SkyPass sky;
    detail::TerrainPass terrain;
    detail::LayersPass layers;
    detail::OverlayPass overlays;
    detail::ToneMapPass tonemap;
    detail::ParticlesPass particles;
    std::unique_ptr<detail::FroxelPass> froxel;         // built on first use
    std::unique_ptr<detail::ShadowMapPass> shadow_map;  // built on first use
    std::unique_ptr<detail::SunVolume> sun_volume;      // built on first use
    detail::LightVolumeTexture light_volume;            // set_light_volume
    std::optional<std::pair<const geometry::Medium*, geometry::HeightFog>> sun_medium;
    std::optional<geometry::FogPartition> partition;
    double layer_scale = 0.5;
    double froxel_resolution = 1.0;  // set_froxel_resolution
    bool layers_multisampled = false;
    bool drawing_still = false;  // Renderer::render's draws (FrameContext::still)
    detail::RenderTargets targets;
    SunLight sun;
    FrameStats stats;
    int pending_uploads = 0;
    std::optional<FrameContext> last_frame;
    // The origin the passes' coordinates are measured from (render_origin.hpp), chosen by the
    // terrain. With a non-zero one the passes get moved copies of what the renderer is given,
    // made again only when that changes; what it was given is kept (by reference, as the
    // setters say) so that a terrain moving the origin moves everything else with it.
    glm::dvec3 origin{0.0};
    struct TerrainSource {
        const geometry::Terrain* terrain = nullptr;
        double exaggeration = 1.0;
        bool surround = true;
    };
    std::optional<TerrainSource> terrain_source;
    std::optional<std::pair<const geometry::LayerBase*, geometry::LayerOptions>> layers_source;
    std::optional<std::pair<const geometry::ParticleCloud*, ParticleStyle>> particles_source;
    std::optional<std::pair<const geometry::Medium*, geometry::HeightFog>> sun_medium_source;
    std::optional<std::pair<const geometry::Medium*, geometry::FroxelOptions>> froxel_source;
    std::shared_ptr<const geometry::LightVolume> light_source;
    const geometry::Medium* light_medium_source = nullptr;
    std::map<std::string, OverlayMesh> overlay_sources;  // only while the origin is not zero
    // The moved copies, each keyed on what tells its source's content apart.
    detail::MovedCopy<geometry::Terrain, std::tuple<const double*, std::size_t, double, double>> moved_terrain;
    detail::MovedCopy<geometry::LayerBase, std::pair<const geometry::LayerBase*, const glm::dvec3*>> moved_layers;
    detail::MovedCopy<geometry::ParticleCloud,
                      std::tuple<const geometry::ParticleCloud*, const geometry::Particle*, std::size_t>>
        moved_particles;
    detail::MovedCopy<geometry::LightVolume, std::shared_ptr<const geometry::LightVolume>> moved_light;
    detail::MovedMedium froxel_medium, sun_medium_copy, light_medium;

    bool moved() const { return origin != glm::dvec3(0.0); }
    void apply_terrain();
    void apply_layers();
    void apply_particles();
    void apply_sun_medium();
    void apply_light_volume();
    void apply_froxel_fog();
    PassTimer shadow_timer{"shadow map"}, sky_timer{"sky"}, terrain_timer{"terrain"}, layers_timer{"layers"},
        resolve_timer{"resolve"}, overlays_timer{"overlays"}, tonemap_timer{"tonemap"}, particles_timer{"particles"},
        sun_volume_timer{"sun volume"}, ground_shade_timer{"ground shade"};

    //! The sun's shadow map brought up to date for the frame; null without terrain shadows.
    const detail::ShadowMapPass* update_shadow_map(const FrameContext& frame)
    {
        shadow_timer.forget();
        if (!sun.terrain_shadows || !terrain.has_terrain())
            return nullptr;
        // Over the terrain alone, so that its shadows do not depend on the fog drawn: a point
        // above the terrain's box is never in its shadow (the sun above the horizon), and
        // terrain_shadow.glsl lights what lies outside the map. In view or not, the terrain
        // casts its shadows into the frame.
        if (!shadow_map)
            shadow_map = std::make_unique<detail::ShadowMapPass>();
        const ScopedPassTimer timed(shadow_timer);
        shadow_map->update(terrain, frame.sun_direction, terrain.bounds_min(), terrain.bounds_max(),
                           sun.shadow_map_size, sun.esm_sharpness);
        return shadow_map.get();
    }

    //! The sun volume brought up to date for the frame: of the Medium set_sun_medium gave, else
    //! of the froxel fog's. Null without a Medium.
    const detail::SunVolume* update_sun_volume(const FrameContext& frame, const detail::FroxelPass* fog)
    {
        sun_volume_timer.forget();
        const geometry::Medium* medium = nullptr;
        geometry::HeightFog haze;
        if (sun_medium) {
            medium = sun_medium->first;
            haze = sun_medium->second;
        } else if (fog) {
            medium = fog->medium();
            haze = fog->options().height_fog;
        }
        if (!medium && !haze.enabled() && !sun_volume)
            return nullptr;
        if (!sun_volume)
            sun_volume = std::make_unique<detail::SunVolume>();
        sun_volume->set(medium, haze);
        if (sun_volume->stale(frame.sun_direction)) {
            const ScopedPassTimer timed(sun_volume_timer);
            sun_volume->update(frame.sun_direction);
        } else {
            sun_volume->update(frame.sun_direction);  // drops the volume of a Medium gone
        }
        return sun_volume.get();
    }
};

Renderer::Renderer() : impl_(std::make_unique<Impl>()) {}
Renderer::~Renderer() = default;

void Renderer::Impl::apply_terrain()
{
    if (!terrain_source)
        return;
    const TerrainSource& src = *terrain_source;
    const geometry::Heightfield& hf = src.terrain->heightfield();
    const geometry::Terrain* local = moved_terrain.get(src.terrain, {hf.z.data(), hf.z.size(), hf.x0, hf.y0}, origin);
    if (terrain.set_terrain(*local, src.exaggeration, src.surround))
        ++pending_uploads;
    layers.set_ground(local->heightfield(), src.exaggeration);
}

void Renderer::Impl::apply_layers()
{
    if (!layers_source)
        return;
    const geometry::LayerBase* base = layers_source->first;
    if (layers.set_base(*moved_layers.get(base, {base, base->position.data()}, origin)))
        ++pending_uploads;
    layers.set_options(layers_source->second);
    layers.set_noise_shift(glm::dvec2(origin));
}

void Renderer::Impl::apply_particles()
{
    if (!particles_source)
        return;
    const geometry::ParticleCloud* cloud = particles_source->first;
    const geometry::ParticleCloud* local =
        moved_particles.get(cloud, {cloud, cloud->particles.data(), cloud->particles.size()}, origin);
    if (particles.set_particles(*local, particles_source->second))
        ++pending_uploads;
}

void Renderer::Impl::apply_sun_medium()
{
    if (!sun_medium_source) {
        sun_medium.reset();
        sun_medium_copy.clear();
        return;
    }
    const auto& [medium, haze] = *sun_medium_source;
    sun_medium.emplace(sun_medium_copy.get(medium, detail::medium_key(medium), origin),
                       moved() ? detail::moved(haze, origin) : haze);
}

void Renderer::Impl::apply_light_volume()
{
    const bool own = moved_light.get(light_source.get(), light_source, origin) == light_source.get();
    light_volume.set(own ? light_source : moved_light.copy(),
                     light_medium.get(light_medium_source, detail::medium_key(light_medium_source), origin));
}

void Renderer::Impl::apply_froxel_fog()
{
    if (!froxel_source)
        return;
    if (!froxel)
        froxel = std::make_unique<detail::FroxelPass>();
    geometry::FroxelOptions options = froxel_source->second;
    if (moved())
        options.height_fog = detail::moved(options.height_fog, origin);
    const geometry::Medium* medium = froxel_source->first;
    froxel->set_fog(froxel_medium.get(medium, detail::medium_key(medium), origin), options);
    froxel->set_resolution(froxel_resolution);
}

void Renderer::set_terrain(const geometry::Terrain& terrain, double exaggeration, bool surround)
{
    Impl& r = *impl_;
    r.terrain_source = Impl::TerrainSource{&terrain, exaggeration, surround};
    const glm::dvec3 origin = detail::render_origin_for(terrain.bounds());
    if (origin == r.origin) {
        r.apply_terrain();
        return;
    }
    // Everything moves with the origin: uploaded again from what the renderer was given.
    r.origin = origin;
    r.apply_terrain();
    r.apply_layers();
    r.apply_particles();
    r.apply_sun_medium();
    r.apply_light_volume();
    r.apply_froxel_fog();
    for (const auto& [name, mesh] : r.overlay_sources)
        r.overlays.set(name, r.moved() ? detail::moved(mesh, r.origin) : mesh);
    if (!r.moved())
        r.overlay_sources.clear();
}

void Renderer::set_layers(const geometry::LayerBase& base, const geometry::LayerOptions& options)
{
    impl_->layers_source.emplace(&base, options);
    impl_->apply_layers();
}

void Renderer::clear_layers()
{
    impl_->layers.clear();
    impl_->layers_source.reset();
    impl_->moved_layers.clear();
}

void Renderer::set_terrain_resolution(double scale) { impl_->terrain.set_resolution(scale); }

void Renderer::set_froxel_resolution(double scale)
{
    impl_->froxel_resolution = std::isfinite(scale) ? std::clamp(scale, 0.125, 1.0) : 1.0;
    if (impl_->froxel)
        impl_->froxel->set_resolution(impl_->froxel_resolution);
}

void Renderer::set_particle_resolution(double scale) { impl_->particles.set_resolution(scale); }

void Renderer::set_layer_resolution(double scale, bool multisampled)
{
    impl_->layer_scale = std::isfinite(scale) ? std::clamp(scale, 0.125, 1.0) : 1.0;
    impl_->layers_multisampled = multisampled && impl_->layer_scale == 1.0;
}

void Renderer::set_overlay(const std::string& name, const OverlayMesh& mesh)
{
    Impl& r = *impl_;
    if (r.moved()) {
        r.overlay_sources[name] = mesh;
        r.overlays.set(name, detail::moved(mesh, r.origin));
    } else {
        r.overlays.set(name, mesh);
    }
    ++r.pending_uploads;
}

void Renderer::set_overlay_style(const std::string& name, const OverlayStyle& style)
{
    impl_->overlays.set_style(name, style);
}

void Renderer::remove_overlay(const std::string& name)
{
    impl_->overlays.remove(name);
    impl_->overlay_sources.erase(name);
}

void Renderer::set_sun(const SunLight& sun) { impl_->sun = sun; }

void Renderer::set_sun_medium(const geometry::Medium* medium, const geometry::HeightFog& haze)
{
    impl_->sun_medium_source.emplace(medium, haze);
    impl_->apply_sun_medium();
}

void Renderer::clear_sun_medium()
{
    impl_->sun_medium_source.reset();
    impl_->apply_sun_medium();
}

void Renderer::set_light_volume(std::shared_ptr<const geometry::LightVolume> volume, const geometry::Medium* medium)
{
    impl_->light_source = std::move(volume);
    impl_->light_medium_source = medium;
    impl_->apply_light_volume();
}

void Renderer::set_fog_partition(const std::optional<geometry::FogPartition>& partition)
{
    if (partition)
        geometry::validate_fog_partition(*partition);
    impl_->partition = partition;
}

void Renderer::set_particles(const geometry::ParticleCloud& cloud, const ParticleStyle& style)
{
    impl_->particles_source.emplace(&cloud, style);
    impl_->apply_particles();
}

void Renderer::clear_particles()
{
    impl_->particles.clear();
    impl_->particles_source.reset();
    impl_->moved_particles.clear();
}

const AttenuationBuffer& Renderer::attenuation() const { return impl_->particles.buffer(); }
void Renderer::set_froxel_fog(const geometry::Medium* medium, const geometry::FroxelOptions& options)
{
    impl_->froxel_source.emplace(medium, options);
    impl_->apply_froxel_fog();
}

void Renderer::clear_froxel_fog()
{
    if (impl_->froxel)
        impl_->froxel->clear();
    impl_->froxel_source.reset();
    impl_->froxel_medium.clear();
}

FogBuffer Renderer::read_froxel_fog()
{
    Impl& r = *impl_;
    if (!r.froxel || !r.froxel->enabled() || !r.last_frame)
        return {};
    return r.froxel->read_fog(*r.last_frame, r.terrain);
}

void Renderer::draw(const Camera& world_camera, int width, int height)
{
    Impl& r = *impl_;
    const Camera camera = detail::moved(world_camera, r.origin);
    const auto start = std::chrono::steady_clock::now();
    r.targets.ensure(width, height);
    glm::dvec3 scene_min = r.terrain.bounds_min(), scene_max = r.terrain.bounds_max();
    r.layers.extend_bounds(scene_min, scene_max);
    r.overlays.extend_bounds(scene_min, scene_max);
    r.particles.extend_bounds(scene_min, scene_max);
    const detail::FroxelPass* fog = r.froxel && r.froxel->enabled() ? r.froxel.get() : nullptr;
    if (fog)
        r.froxel->extend_bounds(scene_min, scene_max);
    const glm::dvec3 terrain_extent = r.terrain.bounds_max() - r.terrain.bounds_min();
    FrameContext frame =
        detail::make_frame_context(camera, r.sun, width, height, scene_min, scene_max,
                                   std::hypot(std::max(terrain_extent.x, 0.0), std::max(terrain_extent.y, 0.0)));
    frame.still = r.drawing_still;
    if (r.partition) {
        frame.partitioned = true;
        frame.partition = glm::vec4(r.partition->near_start, r.partition->near_end, r.partition->particle_share,
                                    r.partition->particle_band);
        const geometry::ParticleDepthRange depth = geometry::particle_depth_range(*r.partition);
        frame.partition_depth = glm::vec2(depth.start, depth.full);
    }
    const detail::ShadowMapPass* shadow = r.update_shadow_map(frame);
    const detail::SunVolume* sun_volume = r.update_sun_volume(frame, fog);
    r.ground_shade_timer.forget();
    if (r.terrain.fog_shade_stale(sun_volume, frame.sun_direction)) {
        const ScopedPassTimer timed(r.ground_shade_timer);
        r.terrain.set_fog_shade(sun_volume, frame.sun_direction);
    } else {
        r.terrain.set_fog_shade(sun_volume, frame.sun_direction);  // drops the shade of a fog gone
    }
    if (fog) {  // before the scene: is the fog in view
        r.froxel->prepare(frame, shadow);
        r.froxel->set_sun_volume(sun_volume);
        r.froxel->set_light_volume(&r.light_volume);
    }
    // With froxel fog the layers and the particles come after its apply and read it at their
    // own depth (FroxelPass::bind_apply + froxel_fog(world) in their fragment shaders).
    const bool layers_multisampled = r.layers_multisampled && !fog;
    r.layers.set_fog(fog, shadow, sun_volume);
    r.layers.set_light_volume(&r.light_volume);
    r.particles.set_fog(fog, shadow, sun_volume);
    r.particles.set_light_volume(&r.light_volume);
    r.targets.bind_for_drawing();
    {
        const ScopedPassTimer timed(r.sky_timer);
        r.sky.draw(frame, r.terrain);
    }
    {
        const ScopedPassTimer timed(r.terrain_timer);
        const detail::FrameSamples samples = r.targets.frame_samples();
        r.terrain.draw(frame, shadow, &samples);
    }
    if (layers_multisampled) {  // layers straight into the multisampled frame
        const ScopedPassTimer timed(r.layers_timer);
        if (r.layers.draw(frame))
            ++r.pending_uploads;
    }
    {
        const ScopedPassTimer timed(r.resolve_timer);
        const glm::vec2 planes = detail::depth_planes(frame);
        r.targets.resolve(planes.x, planes.y);
    }
    if (fog) {  // the volume from the frame's depth, then the fog on the resolved frame
        const detail::FrameSamples samples = r.targets.frame_samples();
        r.froxel->update(frame, r.terrain, r.targets.resolved_depth(), &samples);
        r.froxel->apply(frame, r.targets.hdr_color(), r.targets.resolved_depth(), samples);
    }
    if (!layers_multisampled) {  // layers in their own target, composited after the resolve
        const ScopedPassTimer timed(r.layers_timer);
        // The samples' colour, unless the froxels' fog went into the resolved frame since.
        detail::FrameSamples below = r.targets.frame_samples();
        if (fog)
            below.color = 0;
        if (r.layers.draw_reduced(frame, r.layer_scale, r.targets.hdr_framebuffer(), r.targets.resolved_depth(), below))
            ++r.pending_uploads;
    }
    const bool particles = r.particles.has_particles();
    bool rebuilt = false;
    if (particles) {  // over the terrain and the layers, soft where they meet the terrain
        const ScopedPassTimer timed(r.particles_timer);
        // The samples' colour, unless fog went into the resolved frame since (the froxels', the
        // layers').
        detail::FrameSamples below = r.targets.frame_samples();
        if (fog || (!layers_multisampled && r.layers.has_layers()))
            below.color = 0;
        rebuilt = r.particles.draw(frame, r.targets.hdr_framebuffer(), r.targets.resolved_depth(), &below);
    }
    {
        const ScopedPassTimer timed(r.tonemap_timer);
        glBindFramebuffer(GL_FRAMEBUFFER, r.targets.display_framebuffer());
        glViewport(0, 0, width, height);
        r.tonemap.draw(frame, r.targets.hdr_color());
    }
    const bool overlays = r.overlays.has_visible();
    if (overlays) {  // last, over the fog, into the display image (its depth is the terrain's)
        const ScopedPassTimer timed(r.overlays_timer);
        r.overlays.draw(frame);
    }
    glFinish();
    detail::check_gl_errors("Renderer::draw");

    r.stats = {};
    if (shadow && r.shadow_timer.ran())
        r.stats.passes.push_back(r.shadow_timer.result());
    r.stats.shadow_map_updates = r.shadow_map ? r.shadow_map->updates() : 0;
    for (const PassTimer* t : {&r.sun_volume_timer, &r.ground_shade_timer})
        if (t->ran())
            r.stats.passes.push_back(t->result());
    r.stats.sun_volume_updates = r.sun_volume ? r.sun_volume->updates() : 0;
    for (const PassTimer* t : {&r.sky_timer, &r.terrain_timer, &r.layers_timer, &r.resolve_timer, &r.tonemap_timer})
        r.stats.passes.push_back(t->result());
    if (particles) {
        // The buffer's build is part of the particles' pass; reported apart when it ran.
        if (rebuilt)
            r.stats.passes.push_back(
                {"attenuation", r.particles.buffer().last_build_ms(), r.particles.buffer().last_build_ms()});
        r.stats.passes.push_back(r.particles_timer.result());
        r.stats.particles = int(r.particles.count());
        r.stats.attenuation_rebuilds = rebuilt ? 1 : 0;
        r.stats.particle_light_rebuilds = r.particles.last_light_rebuilt() ? 1 : 0;
        r.stats.near_particles = r.particles.last_near_count();
        r.stats.particles_drawn = r.particles.last_drawn_count();
        r.stats.particle_light_bytes = r.particles.light().bytes();
        r.stats.particle_fragments = r.particles.last_fragments();
    }
    if (overlays)
        r.stats.passes.push_back(r.overlays_timer.result());
    if (fog) {
        fog->append_timings(r.stats.passes);
        r.stats.froxel = fog->stats();
    }
    r.stats.uploads = std::exchange(r.pending_uploads, 0);
    r.stats.layers = r.layers.last_layer_count();
    r.stats.layer_triangles = r.layers.last_triangle_count();
    r.stats.terrain_triangles = int(r.terrain.drawn_triangles());
    r.stats.terrain_vertices = r.terrain.vertex_count();
    r.stats.refined_shade_vertices = r.terrain.refined_shade_vertices();
    r.stats.frame_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    r.last_frame = frame;
}

Image Renderer::render(const Camera& camera, int width, int height)
{
    const auto start = std::chrono::steady_clock::now();
    struct StillFrames {  // also when a draw throws
        bool& drawing;
        explicit StillFrames(bool& flag) : drawing(flag) { drawing = true; }
        ~StillFrames() { drawing = false; }
    } still(impl_->drawing_still);
    draw(camera, width, height);
    const FroxelStats& froxel = impl_->stats.froxel;
    if (froxel.visible && !froxel.converged)  // a moving view's froxels: this view held is a still
        draw(camera, width, height);
    Image image{width, height, impl_->targets.read_rgba()};
    detail::check_gl_errors("Renderer::render");
    impl_->stats.frame_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return image;
}

void Renderer::present(int framebuffer_width, int framebuffer_height) const
{
    const Impl& r = *impl_;
    if (r.targets.width() <= 0 || framebuffer_width <= 0 || framebuffer_height <= 0)
        return;
    glBlitNamedFramebuffer(r.targets.display_framebuffer(), 0, 0, 0, r.targets.width(), r.targets.height(), 0, 0,
                           framebuffer_width, framebuffer_height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
    // What draws next (a UI) draws over the frame in the window.
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, framebuffer_width, framebuffer_height);
}

const FrameStats& Renderer::last_stats() const { return impl_->stats; }

glm::dvec3 Renderer::origin() const { return impl_->origin; }

RadianceImage Renderer::read_radiance() const
{
    const detail::RenderTargets& t = impl_->targets;
    RadianceImage image{t.width(), t.height(), {}};
    image.rgba.resize(std::size_t(image.width) * std::size_t(image.height) * 4);
    if (image.rgba.empty())
        return image;
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(t.hdr_color(), 0, GL_RGBA, GL_FLOAT, GLsizei(image.rgba.size() * sizeof(float)),
                      image.rgba.data());
    detail::flip_rows(image.rgba, std::size_t(image.width) * 4);
    detail::check_gl_errors("Renderer::read_radiance");
    return image;
}

RadianceSamples Renderer::read_radiance_samples() const
{
    const detail::RenderTargets& t = impl_->targets;
    RadianceSamples out;
    out.width = t.width();
    out.height = t.height();
    out.samples = std::max(t.resolved_samples(), 1);
    out.rgba = t.read_samples();
    // GL's sample positions run up the pixel, the image's rows down.
    out.offsets.assign(t.sample_offsets(), t.sample_offsets() + 2 * out.samples);
    for (int s = 0; s < out.samples; ++s)
        out.offsets[std::size_t(2 * s + 1)] = -out.offsets[std::size_t(2 * s + 1)];
    detail::check_gl_errors("Renderer::read_radiance_samples");
    return out;
}

std::optional<glm::dvec3> Renderer::pick(int x, int y) const
{
    const Impl& r = *impl_;
    if (!r.last_frame || x < 0 || y < 0 || x >= r.targets.width() || y >= r.targets.height())
        return std::nullopt;
    const float depth = r.targets.read_depth(x, y);
    if (depth >= 1.0f)
        return std::nullopt;
    const FrameContext& f = *r.last_frame;
    const glm::dvec4 ndc((x + 0.5) / f.width * 2.0 - 1.0, 1.0 - (y + 0.5) / f.height * 2.0, depth * 2.0 - 1.0, 1.0);
    const glm::dvec4 local = glm::inverse(f.projection * f.view) * ndc;
    return glm::dvec3(local) / local.w + r.origin;
}

}  // namespace kiri::render
