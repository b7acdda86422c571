// The look records of a scene for the renderer (render_scene.hpp):
// projected decals, fog volumes, irradiance volumes, reflection probes, and
// the post-processing and shadow settings of the environment and
// rayrai_render records.  Called by prepareScene().
#include "render/render_effects.hpp"

#include <algorithm>
#include <cmath>

#include "scene/reader.hpp"

namespace rscene::render {
namespace {

std::uint32_t lineOf(const Document& doc, int recordIndex) {
  return recordIndex >= 0 && std::size_t(recordIndex) < doc.records.size() ? doc.records[std::size_t(recordIndex)].line
                                                                            : 0;
}

float nonNegative(double v) { return std::isfinite(v) ? float(std::max(v, 0.0)) : 0.f; }

// A color as written (display, gamma 2.2) in linear light, as the shaders
// take the ambient and fog colors.
Eigen::Vector3f linear(const Eigen::Vector3d& c) {
  Eigen::Vector3f out;
  for (int i = 0; i < 3; ++i) out[i] = float(std::pow(std::isfinite(c[i]) ? std::max(c[i], 0.0) : 0.0, 2.2));
  return out;
}

// Unit cube [-1, 1]^3 -> world of a box record: pose x scale x halfExtents.
Eigen::Affine3d boxWorld(const Pose& pose, const Eigen::Vector3d& scale, const Eigen::Vector3d& halfExtents) {
  return Eigen::Translation3d(pose.position) * pose.orientation.normalized() *
         Eigen::Scaling(Eigen::Vector3d(scale.cwiseProduct(halfExtents).cwiseAbs()));
}

Eigen::AlignedBox3d cubeBounds(const Eigen::Affine3d& world) {
  return transformBox(world, Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1)));
}

}  // namespace

void prepareEffects(const Document& doc, const Scene& s, RenderScene& out) {
  for (const Decal& d : s.decals) {
    if (!d.enabled || d.hiddenByGroup) continue;
    RenderDecal r;
    r.world = boxWorld(d.world, d.scale, d.halfExtents);
    r.color = d.color.cast<float>();
    r.edgeFade = nonNegative(d.edgeFade);
    r.normalFade = nonNegative(d.normalFade);
    r.upperFade = nonNegative(d.upperFade);
    r.lowerFade = nonNegative(d.lowerFade);
    r.albedoTexture = d.albedoTexture;
    r.emissionTexture = d.emissionTexture;
    r.normalTexture = d.normalTexture;
    r.ormTexture = d.ormTexture;
    r.uvScale = d.uvScale.cast<float>();
    r.uvOffset = d.uvOffset.cast<float>();
    r.albedoMix = float(std::clamp(d.albedoMix, 0.0, 1.0));
    r.emissionEnergy = nonNegative(d.emissionEnergy);
    r.normalStrength = float(d.normalStrength);
    r.ormStrength = float(d.ormStrength);
    if (d.distanceFadeEnabled) {
      r.fadeBegin = nonNegative(d.distanceFadeBegin);
      r.fadeLength = std::max(nonNegative(d.distanceFadeLength), 1e-3f);
    }
    r.bounds = cubeBounds(r.world);
    r.line = lineOf(doc, d.recordIndex);
    if (d.recordIndex >= 0 && std::size_t(d.recordIndex) < doc.records.size()) {
      Diagnostics unused;
      RecordReader reader(doc, std::size_t(d.recordIndex), unused);
      const char* fields[4] = {"albedoTexture", "emissionTexture", "normalTexture", "ormTexture"};
      for (std::size_t k = 0; k < 4; ++k) r.textureColumns[k] = reader.columnOf(fields[k]);
    }
    out.decals.push_back(std::move(r));
  }
  for (const LocalFog& f : s.localFogs) {
    if (!f.enabled || f.hiddenByGroup || !(f.radius > 0) || !(f.density > 0)) continue;
    RenderFog r;
    r.center = f.center;
    r.radius = float(f.radius);
    r.density = nonNegative(f.density);
    r.edgeFade = float(std::clamp(f.edgeFade, 0.0, 1.0));
    r.noiseScale = nonNegative(f.noiseScale);
    r.noiseStrength = float(std::clamp(f.noiseStrength, 0.0, 1.0));
    r.color = linear(f.color);
    r.line = lineOf(doc, f.recordIndex);
    out.fogs.push_back(r);
  }
  for (const IrradianceVolume& v : s.irradianceVolumes) {
    if (!v.enabled || v.hiddenByGroup) continue;
    RenderIrradiance r;
    r.world = boxWorld(v.world, v.scale, v.halfExtents);
    r.color = linear(v.color.head<3>()) * nonNegative(v.strength);
    r.edgeFade = nonNegative(v.edgeFade);
    r.normalBias = float(v.normalBias);
    r.bounds = cubeBounds(r.world);
    r.line = lineOf(doc, v.recordIndex);
    out.irradianceVolumes.push_back(r);
  }
  for (const ReflectionProbe& p : s.reflectionProbes) {
    if (!p.enabled || p.hiddenByGroup) continue;
    RenderProbe r;
    r.position = p.position;
    r.radius = nonNegative(p.radius);
    r.strength = nonNegative(p.strength);
    r.boxProjection = p.boxProjection;
    r.box = Eigen::AlignedBox3d(p.boxMin.cwiseMin(p.boxMax), p.boxMin.cwiseMax(p.boxMax));
    auto side = [](std::int64_t v, int lo, int hi) { return int(std::clamp<std::int64_t>(v, lo, hi)); };
    r.cubemapSize = side(p.cubemapSize, 8, 2048);
    r.prefilteredResolution = side(p.prefilteredResolution, 8, 2048);
    r.prefilteredMipLevels = side(p.prefilteredMipLevels, 1, 12);
    r.prefilteredSamples = side(p.prefilteredSamples, 1, 4096);
    r.irradianceResolution = side(p.irradianceResolution, 4, 512);
    r.irradianceSamples = side(p.irradianceSamples, 1, 4096);
    r.brdfLutSize = side(p.brdfLutSize, 8, 1024);
    r.brdfLutSamples = side(p.brdfLutSamples, 1, 8192);
    r.captureShadows = p.captureShadows;
    r.captureBackground = p.captureEnvironmentBackground;
    r.drawVisuals = p.captureDrawVisualizationObjects;
    r.drawPointClouds = p.captureDrawPointClouds;
    r.exposure = nonNegative(p.captureEnvironmentExposure);
    r.line = lineOf(doc, p.recordIndex);
    out.probes.push_back(r);
  }

  // Environment and rayrai_render: post-processing and shadow defaults.
  const Environment& env = s.environment;
  const RenderSettings& rs = s.renderSettings;
  Look& e = out.environment;
  e.heightFog = env.heightFogEnabled && env.heightFogDensity > 0;
  e.heightFogDensity = nonNegative(env.heightFogDensity);
  e.heightFogBase = float(env.heightFogBaseHeight);
  e.heightFogFalloff = nonNegative(env.heightFogFalloff);
  e.environmentIntensity = nonNegative(rs.recordIndex >= 0 && rs.custom ? rs.pbrEnvironmentIntensity
                                                                        : env.pbrEnvironmentIntensity);
  e.bloomIntensity = nonNegative(env.bloomIntensity);
  e.bloomThreshold = nonNegative(env.bloomThreshold);
  e.bloomRadius = nonNegative(env.bloomRadius);
  e.fxaa = env.fxaa;
  e.ssao = env.ssao;
  e.autoExposure = rs.autoExposure;
  e.autoExposureKey = nonNegative(rs.autoExposureKey);
  e.depthOfField = rs.depthOfField && rs.depthOfFieldAperture > 0;
  e.focusDistance = nonNegative(rs.depthOfFieldFocusDistance);
  e.aperture = nonNegative(rs.depthOfFieldAperture);
  e.preset = rs.preset;
  e.customShadows = rs.recordIndex >= 0 && rs.custom;
  if (e.customShadows) {
    e.shadowResolution = int(std::clamp<std::int64_t>(rs.shadowResolution, 0, 16384));
    e.shadowBias = float(rs.shadowBias);
    e.shadowStrength = float(std::clamp(rs.shadowStrength, 0.0, 1.0));
    e.shadowPcfRadius = nonNegative(rs.shadowPcfRadius);
  }
  if (env.shadowMapSize > 0) e.shadowMapSize = int(std::min<std::int64_t>(env.shadowMapSize, 16384));
  e.shadowedLightBudget = int(std::clamp<std::int64_t>(env.shadowedLightBudget, 0, 1 << 20));
  e.msaaSamples = int(std::clamp<std::int64_t>(rs.msaaSamples, 0, 64));
}

}  // namespace rscene::render
