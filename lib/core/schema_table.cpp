// The schema table: the one place in the project that knows record kinds,
// their positional fields and their keys.  Everything else (loader, writer,
// validator, JSON, diff, typed scene view, man page) reads it through
// schema.hpp.  Adding a key is a one-word change to a line below.
//
// Field syntax:  name:type[@arg][=default]
//   types  num int u64 flag text path id ref name vec2 vec3 quat color
//          nums ints vec3s colors xforms strs
//   rgb/rgba (positional only) are colors spread over 3/4 tokens; csv3 is
//   a vec3 written as one CSV token in a positional slot;
//   vec3/quat positionals span 3/4 tokens.
//   @arg   for name: the enumeration; for ref: what it refers to
//          (node material contact asset resource texslot terrain body)
//   =value the default Engine 2 assumes when the key is absent
#include "core/schema_table.hpp"

namespace rscene::table {

// clang-format off
const KindRow kKinds[] = {
{"raisim_engine_scene", 0, Role::Singleton, "", "",
 "version:int", ""},
{"time_step", 1, Role::Singleton, "", "",
 "dt:num=0.0025", ""},
{"gravity", 2, Role::Singleton, "", "",
 "gravity:vec3=0,0,-9.81", ""},
{"solver", 3, Role::Singleton, "", "",
 "iterations:int=80 tolerance:num=1e-07 erp:num=0.2 mode:name@solver_mode=accurate",
 "erp2:num=0 defaultFriction:num=0.8 defaultRestitution:num=0 defaultRestitutionThreshold:num=0.001 "
 "defaultStaticFriction:num=0.8 defaultStaticFrictionVelocityThreshold:num=0.001 defaultRollingFriction:num=0 "
 "defaultSpinningFriction:num=0 contactAlphaInit:num=1 contactAlphaMin:num=1 contactAlphaDecay:num=1 "
 "contactMaxIterations:int=80 contactThreshold:num=1e-07 contactGjkMaxIterations:int=32 contactGjkTolerance:num=1e-06 "
 "contactEpaMaxIterations:int=64 contactEpaTolerance:num=0.0001 maxContactsPerPair:int=8 sweptCcdEnabled:flag=false "
 "sweptCcdMinSpeed:num=0 sweptCcdSpeculativeMargin:num=0.0001 sleepingEnabled:flag=true "
 "sleepingLinearVelocityThreshold:num=0.002 sleepingAngularVelocityThreshold:num=0.01 sleepingQuietSteps:int=5 "
 "broadphaseType:name@broadphase=sap3_axis broadphaseWorldMin:vec3=-100,-100,-100 broadphaseWorldMax:vec3=100,100,100 "
 "broadphaseCellSize:vec3=1,1,1 broadphaseUseWorldBounds:flag=false broadphasePadding:num=0.5 "
 "broadphaseMaxCellsPerAxis:int=128 broadphaseMaxCellsPerObject:int=64 worldTime:num=0 "
 "fixedContactSolverIterationOrder:flag=false"},
{"snapping", 4, Role::Singleton, "", "",
 "grid:flag angle:flag scale:flag reserved1:flag reserved2:flag reserved3:flag reserved4:flag reserved5:flag "
 "gridSize:num=0.1 angleDegrees:num=15 scaleStep:num=0.1 reserved6:num=0",
 "surfaceNormal:vec3=0,0,1"},
{"asset_root", 5, Role::Singleton, "", "",
 "path:path=.", ""},
{"scene_graph", 6, Role::Singleton, "", "", "",
 "inheritedTransforms:flag=true keepWorldTransformOnReparent:flag=true dragReparenting:flag=true "
 "packedSceneOverrides:flag=true transformSpace:name@transform_space=global"},
{"prefab_override", 7, Role::Plain, "", "",
 "path:ref@node", "property:text value:text"},
{"editor_ux", 8, Role::Singleton, "", "", "",
 "multiSelect:flag=true copyPaste:flag=true duplicate:flag=true transformLocalSpace:flag=false "
 "selectionFilters:flag=true strongUndoGrouping:flag=true selectionFilterKinds:strs"},
{"render_bake", 9, Role::Singleton, "", "", "",
 "probeCaptureOnSave:flag=false lightmapBakeEnabled:flag=false irradianceBakeEnabled:flag=false "
 "renderDiagnostics:flag=false lightmapResolution:int=1024 probeCubemapSize:int=256 outputDirectory:path=bakes"},
{"environment", 10, Role::Singleton, "", "",
 "background:rgb=0.38,0.38,0.38 ambient:rgb=0.15,0.16,0.2 fogDensity:num=0 shadows:flag=true reserved1:flag=true "
 "reserved2:num=10 envMapPath:path",
 "fogColor:color exposure:num=1 gamma:num=2.2 bloomIntensity:num=0 bloomThreshold:num=1 bloomRadius:num=4 "
 "shadowMapSize:int=0 shadowedLightBudget:int=0 backgroundMode:name@background_mode=rayrai_sky "
 "colorMode:name@color_mode pbrEnvironmentLightingTint:color pbrEnvironmentIntensity:num=1 fxaa:flag=false ssao:flag=false "
 "heightFogEnabled:flag=false heightFogDensity:num=0 heightFogBaseHeight:num=0 heightFogFalloff:num=0.35"},
{"weather", 11, Role::Singleton, "", "",
 "enabled:flag=true",
 "preset:name@weather_preset=clear quality:name@weather_quality seed:int timeOfDay:num=12 latitude:num longitude:num "
 "year:int month:int day:int windDirection:vec3 windSpeed:num transitionSeconds:num affectSensors:flag "
 "cloudCoverage:num cloudDensity:num precipitationRate:num rainOcclusionStrength:num fogDensity:num=0 "
 "visibilityMeters:num fogColor:color fogAnisotropy:num humidity:num wetness:num "
 "wetnessAccumulationEnabled:flag wetnessAccumulationRate:num wetnessDryingRate:num snowCoverage:num "
 "lightningRate:num lightningLocalPointLightEnabled:flag lightningLocalPointDistance:num "
 "lightningLocalPointRadius:num lightningLocalPointIntensity:num thunderSpeedOfSound:num airTurbidity:num "
 "groundAlbedo:num sunDiskSize:num moonDiskSize:num cloudAltitudeMeters:num cloudThicknessMeters:num "
 "cloudShadowStrength:num cloudScale:num cloudAnimationSpeed:num lensDropletsEnabled:flag lensDropletStrength:num "
 "useExplicitSunAngles:flag=false sunAzimuthDegrees:num=180 sunElevationDegrees:num=42"},
{"rayrai_render", 12, Role::Singleton, "", "", "",
 "preset:name@render_preset=balanced custom:flag=false colorMode:name@color_mode viewerMsaaSamples:int=4 "
 "textureAnisotropy:num shadowResolution:int=2048 shadowBias:num=0.0008 shadowStrength:num=0.85 shadowPcfRadius:num=1.25 "
 "directionalShadowCascadeCount:int directionalShadowCascadeLambda:num directionalShadowCascadeMaxDistance:num "
 "highFidelityPbr:flag pbrToneMapping:flag pbrExposure:num=1 pbrEnvironmentIntensity:num=1 addViewerFillLights:flag "
 "reflectiveGround:flag=false autoExposure:flag=false autoExposureKey:num=0.18 autoExposureSpeed:num=0.05 "
 "volumetricFog:flag=false volumetricFogDensity:num=0 volumetricLightStrength:num=0 contactShadows:flag=false "
 "contactShadowsLength:num=0.12 contactShadowsStrength:num=0.7 screenSpaceReflections:flag=false "
 "screenSpaceReflectionStrength:num=0 motionBlur:flag=false motionBlurDirection:vec2 motionBlurStrength:num "
 "depthOfField:flag=false depthOfFieldFocusDistance:num=5 depthOfFieldAperture:num=0 diagnostics:flag"},
{"material", 13, Role::Plain, "", "",
 "name:text color:rgba=0.55,0.62,0.72,1 metallic:num=0 roughness:num=0.55 emissive:rgb=0,0,0 "
 "emissiveStrength:num=0 doubleSided:flag=false albedoTexture:path normalTexture:path metallicTexture:path "
 "roughnessTexture:path aoTexture:path emissiveTexture:path",
 "id:id type:name@material_type metallicRoughnessTexture:path uvScale:vec2 uvOffset:vec2 uvRotation:num "
 "textureAnisotropy:num alphaMode:name@alpha_mode=opaque alphaCutoff:num=0.5 useVertexColorAsAlbedo:flag "
 "vertexColorIsSrgb:flag textureBlendFactor:num ao:num blendMode:name renderPriority:int alphaHashScale:num "
 "alphaAntialiasing:name alphaAntialiasingEdge:num distanceFadeMode:name distanceFadeMin:num distanceFadeMax:num "
 "proximityFadeEnabled:flag proximityFadeDistance:num aoStrength:num aoLightAffect:num emissionOperator:name "
 "specularFactor:num specularColor:color diffuseMode:name specularMode:name normalStrength:num "
 "normalConvention:name ior:num transmission:num transmissionTexture:path refraction:num refractionTexture:path "
 "refractionTextureChannel:name volumeThickness:num thicknessTexture:path volumeAttenuationDistance:num "
 "volumeAttenuationColor:color subsurfaceScatteringStrength:num subsurfaceTexture:path "
 "subsurfaceTransmittanceColor:color subsurfaceTransmittanceTexture:path subsurfaceTransmittanceDepth:num "
 "subsurfaceTransmittanceBoost:num subsurfaceSkinMode:flag backlightColor:color backlightTexture:path "
 "metallicTextureChannel:name roughnessTextureChannel:name aoTextureChannel:name uv2Scale:vec2 uv2Offset:vec2 "
 "uv2Rotation:num textureRepeatMode:name textureFilter:name textureFilterAnisotropy:int albedoTextureForceSrgb:flag "
 "albedoTextureMsdf:flag msdfPixelRange:num msdfOutlineSize:num billboardMode:name billboardKeepScale:flag "
 "particlesAnimHFrames:int particlesAnimVFrames:int particlesAnimLoop:flag particlesAnimFrameProgress:num "
 "particleTrailsEnabled:flag particleTrailLength:num particleTrailTaper:num particleTrailWorldDirection:vec3 "
 "fixedSize:flag fixedSizeScale:num usePointSize:flag pointSize:num useZClipScale:flag zClipScale:num "
 "useFovOverride:flag fovOverrideDegrees:num triplanarEnabled:flag triplanarWorldSpace:flag triplanarScale:vec3 "
 "triplanarOffset:vec3 triplanarSharpness:num uv2TriplanarEnabled:flag uv2TriplanarWorldSpace:flag "
 "uv2TriplanarScale:vec3 uv2TriplanarOffset:vec3 uv2TriplanarSharpness:num clearcoat:num clearcoatRoughness:num "
 "clearcoatTexture:path clearcoatRoughnessTexture:path clearcoatNormalTexture:path iridescence:num "
 "iridescenceThickness:num sheen:num sheenColor:color sheenRoughness:num sheenColorTexture:path "
 "sheenRoughnessTexture:path anisotropy:num anisotropyRotation:num anisotropyTexture:path "
 "anisotropyMapAlphaStrength:flag unlit:flag usePlanarReflection:flag planarReflectionStrength:num "
 "dontReceiveShadows:flag disableAmbientLight:flag disableFog:flag disableSpecularOcclusion:flag "
 "shadowToOpacity:flag thinTwoSidedLighting:flag thinBackDiffuseScale:num thinTransmissionStrength:num "
 "thinTransmissionColor:color foliageType:name foliageWindStrength:num foliageRootHeight:num foliageTipHeight:num "
 "foliageStiffness:num foliageFlutterWeight:num foliageTwoSidedLighting:flag foliageTransmissionStrength:num "
 "foliageTransmissionColor:color foliageWeatherResponse:flag foliageWetResponse:num foliageSnowResponse:num "
 "weatherAffectsWetness:flag weatherAffectsSnow:flag weatherPorosity:num weatherPuddleEligible:flag "
 "weatherSnowEligible:flag weatherMaskTexture:path textureBlendTexture:path rim:num rimTint:num rimPower:num "
 "rimColor:color rimTexture:path growEnabled:flag growAmount:num heightTexture:path heightmapScale:num "
 "heightmapDeepParallax:flag heightmapMinLayers:int heightmapMaxLayers:int heightmapFlip:vec2 heightmapInvert:flag "
 "heightmapVertexDisplacementScale:num heightmapVertexDisplacementMidlevel:num detailMaskTexture:path "
 "detailAlbedoTexture:path detailNormalTexture:path detailAlbedoBlend:num detailBlendMode:name detailUvLayer:name "
 "detailNormalStrength:num aoUsesUv2:flag emissiveUsesUv2:flag lightmapUsesUv2:flag lightmapTexture:path "
 "lightmapStrength:num lightmapTint:color decalDepthBias:flag tinySurfaceDetail:flag depthTest:name depthWrite:name "
 "stencilReference:int stencilRead:flag stencilWrite:flag stencilWriteDepthFail:flag stencilCompare:name "
 "stencilMask:int stencilEffectMode:name stencilEffectColor:color stencilOutlineThickness:num "
 "bentNormalTexture:path bentNormalStrength:num ormTexture:path cullMode:name "
 "albedoTransformAuthored:flag albedoTransformScale:vec2 albedoTransformOffset:vec2 albedoTransformRotation:num "
 "normalTransformAuthored:flag normalTransformScale:vec2 normalTransformOffset:vec2 normalTransformRotation:num "
 "metallicRoughnessTransformAuthored:flag metallicRoughnessTransformScale:vec2 "
 "metallicRoughnessTransformOffset:vec2 metallicRoughnessTransformRotation:num"},
{"contact_material", 14, Role::Plain, "", "",
 "materialA:text materialB:text friction:num restitution:num restitutionThreshold:num staticFriction:num "
 "staticFrictionVelocityThreshold:num rollingFriction:num spinningFriction:num",
 "id:id"},
{"terrain_texture", 15, Role::Plain, "", "",
 "slot:int id:text name:text",
 "color:color=1,1,1,1 albedo:path normal:path displacementTexture:path uvScale:num=1 normalDepth:num aoStrength:num "
 "roughness:num=1 detile:vec2 displacement:vec2"},
{"asset", 16, Role::Plain, "", "",
 "label:text primitive:name@primitive path:path",
 "id:id defaultMaterial:ref@material contactMaterial:ref@contact collisionPath:path "
 "bodyMode:name@body_mode mass:num scale:vec3 quat:quat collidable:flag collisionMode:name@collision_mode "
 "importSource:path importer:text autoReimport:flag generateCollision:flag generatedCollision:name@collision_mode "
 "remapMaterials:flag importScale:num importUpAxis:name importFlipWinding:flag importRecenter:flag "
 "importApplyRootScale:flag materialRemaps:strs importWarnings:strs sourceTimestamp:int sidecarTimestamp:int "
 "meshCollision:name@collision_mode customInertia:flag inertiaDiagonal:vec3 centerOfMass:vec3 coacdThreshold:num "
 "coacdMaxConvexHull:int coacdPreprocess:name coacdSampleResolution:int"},
{"articulated_resource", 17, Role::Plain, "", "",
 "id:text name:text path:path",
 "resourceDirectory:path modules:strs jointOrder:strs doNotCollideWithParent:flag=true convexifyCollisionMeshes:flag=true"},
{"group", 18, Role::Node, "folder_", "",
 "path:text",
 "id:id parentId:ref@node visible:flag=true locked:flag=false expanded:flag=true"},
{"terrain_region", 19, Role::Node, "terrain_", "",
 "path:text xSamples:int ySamples:int xSize:num ySize:num center:vec3",
 "id:id parentGroupId:ref@node location:vec2 material:ref@material contactMaterial:ref@contact "
 "baseTexture:int@texslot=0 visible:flag=true collidable:flag=true castShadow:flag=true receiveShadow:flag=true "
 "sourceKind:name@terrain_source=samples sourcePath:path cloneSource:ref@terrain pngHeightScale:num "
 "pngHeightOffset:num proceduralFrequency:num proceduralZScale:num proceduralOctaves:int "
 "proceduralLacunarity:num proceduralGain:num proceduralStepSize:num proceduralHeightOffset:num "
 "proceduralSeed:int lodLevels:int collisionShapeSize:int textureSplattingEnabled:flag=true heights:nums "
 "texturePrimary:ints textureSecondary:ints textureBlend:nums wetness:nums holes:nums vertexColors:colors"},
{"terrain_splat_layer", 19, Role::Child, "", "terrain_region",
 "terrain:ref@terrain",
 "slot:int@texslot=0 enabled:flag=true strength:num=1 weights:nums"},
{"terrain_foliage_layer", 19, Role::Child, "", "terrain_region",
 "terrain:ref@terrain",
 "id:id name:text enabled:flag=true primitive:name=grass_blade meshPath:path size:vec3=0.06,0.06,0.3 "
 "colorA:color=0.3,0.55,0.2,1 colorB:color=0.45,0.65,0.25,1 density:nums densityPerSquareMeter:num=0 "
 "maxInstances:int=200000 minScale:num=1 maxScale:num=1 randomYawDegrees:num=180 randomPitchDegrees:num=0 "
 "randomRollDegrees:num=0 alignToNormal:flag=false minHeight:num=-1e9 maxHeight:num=1e9 minSlopeDegrees:num=0 "
 "maxSlopeDegrees:num=90 castShadows:flag=false detectable:flag automaticMeshLod:flag "
 "maxRenderedInstances:int=0 renderedInstanceStride:int=1 projectedLod:flag projectedLodMinRadiusPixels:num "
 "projectedLodMaxStride:int doubleBufferedInstanceUploads:flag sortTransparentInstances:flag seed:int=0"},
{"light", 20, Role::Node, "light_", "",
 "path:text direction:vec3 intensity:num",
 "id:id parentGroupId:ref@node type:name@light_type=directional position:vec3=0,0,3 color:color=1,1,1 "
 "ambientColor:color specularColor:color specularIntensity:num attenuationConstant:num=1 "
 "attenuationLinear:num=0.04 attenuationQuadratic:num=0.012 range:num=0 coneAngle:num=30 innerConeAngle:num=18 "
 "radius:num=0 areaSize:vec3=0,0,0 areaRight:vec3 areaUp:vec3 projectorTexture:path projectorStrength:num "
 "projectorUvScale:vec2 projectorUvOffset:vec2 negative:flag=false temperatureEnabled:flag shadows:flag=true "
 "colorTemperature:num distanceFadeEnabled:flag=false distanceFadeBegin:num=40 distanceFadeShadow:num=50 "
 "distanceFadeLength:num=10 shadowResolution:int=0 shadowBias:num=0.0008 shadowStrength:num=1 "
 "shadowPcfRadius:num=1 shadowOrthoHalfSize:num=12.5 shadowNear:num=0.1 shadowFar:num=55 shadowCenter:vec3=0,0,0 "
 "shadowPosition:vec3=0,0,0 shadowUseCustomPosition:flag=false"},
{"camera", 21, Role::Node, "", "",
 "path:text position:vec3 orientation:quat verticalFov:num nearPlane:num farPlane:num width:int height:int "
 "renderMode:name@render_mode enabled:flag",
 "id:id parentGroupId:ref@node projection:name@projection=perspective horizontalFov:num=0 orthoScale:num=10 "
 "previewPostProcessing:flag previewExposure:num previewGamma:num previewDepthOfField:flag "
 "previewFocusDistance:num previewAperture:num outputPath:path"},
{"object", 22, Role::Node, "object_", "",
 "path:text primitive:name@primitive position:vec3 orientation:quat scale:vec3 radius:num height:num mass:num "
 "contactMaterial:ref@contact material:ref@material visualOnly:flag=false visible:flag=true locked:flag=false meshPath:path "
 "bodyMode:name@body_mode collidable:flag=true collisionGroup:u64=1 collisionMask:u64=18446744073709551615",
 "id:id parentGroupId:ref@node semanticClass:text instanceId:int segmentationColor:color materialRemaps:strs "
 "renderMeshPath:path collisionMeshPath:path collisionMode:name@collision_mode=convex_hull "
 "meshCollision:name@collision_mode=convex_hull castShadow:flag=true visualUseMeshColor:flag visualTwoSided:flag visualShadowCasting:name customInertia:flag "
 "inertiaDiagonal:vec3 centerOfMass:vec3 coacdThreshold:num coacdMaxConvexHull:int coacdPreprocess:name "
 "coacdSampleResolution:int"},
{"compound", 23, Role::Node, "", "",
 "path:text position:vec3 orientation:quat scale:vec3 mass:num bodyMode:name@body_mode visible:flag collidable:flag",
 "id:id parentGroupId:ref@node centerOfMass:vec3 inertiaDiagonal:vec3 collisionGroup:u64=1 "
 "collisionMask:u64=18446744073709551615 contactMaterial:ref@contact material:ref@material semanticClass:text"},
{"compound_child", 23, Role::Child, "", "compound",
 "compound:ref@node primitive:name@primitive position:vec3 orientation:quat scale:vec3",
 "size:vec3=0,0,0 radius:num=0 height:num=0 contactMaterial:ref@contact material:ref@material meshPath:path"},
{"deformable", 24, Role::Node, "", "",
 "path:text kind:name@deformable_kind meshPath:path position:vec3 orientation:quat scale:vec3",
 "id:id parentGroupId:ref@node pinnedVertices:ints scale:num=1 totalMass:num=1 distanceCompliance:num=0 "
 "distanceStiffness:num=1000 bendCompliance:num=0 bendStiffness:num=100 youngsModulus:num=0 poissonRatio:num=0.3 "
 "thickness:num=0.002 damping:num=0.01 collisionRadius:num=0.01 iterations:int=20 substeps:int=1 "
 "solverMode:name@deformable_solver=xpbd particleMode:name@particle_mode=skinned particleSpacing:num=0.05 contactMaterial:ref@contact "
 "material:ref@material visible:flag=true collidable:flag=true collisionGroup:u64=1 "
 "collisionMask:u64=18446744073709551615"},
{"granular", 25, Role::Node, "", "",
 "path:text kind:name position:vec3 orientation:quat scale:vec3",
 "id:id parentGroupId:ref@node positions:vec3s radii:nums boxMin:vec3=0,0,0 boxMax:vec3=0,0,0 radius:num=0.01 "
 "spacing:num=0.025 maxParticles:int=20000 velocity:vec3=0,0,0 angularVelocity:vec3=0,0,0 materialId:int=0 "
 "fixed:flag=false density:num=1600 normalStiffness:num=1e6 normalDamping:num=200 tangentialStiffness:num=1e5 "
 "tangentialDamping:num=20 friction:num=0.6 rollingFriction:num=0.05 cohesionStiffness:num=0 "
 "cohesionMaxDistance:num=0 normalContactModel:name@contact_model=hertz substeps:int=2 visible:flag=true"},
{"articulated", 26, Role::Node, "", "",
 "path:text resource:ref@resource position:vec3 orientation:quat visible:flag collidable:flag",
 "id:id parentGroupId:ref@node sourcePath:path resourceDirectory:path modules:strs jointOrder:strs scale:vec3=1,1,1 "
 "doNotCollideWithParent:flag=true convexifyCollisionMeshes:flag=true collisionGroup:u64=1 "
 "collisionMask:u64=18446744073709551615 generalizedCoordinate:nums generalizedVelocity:nums semanticClass:text"},
{"articulated_ik", 26, Role::Child, "", "articulated",
 "articulated:ref@node frame:text target:csv3",
 "enabled:flag=true useOrientation:flag=false orientation:quat=1,0,0,0 maxIterations:int=80 "
 "positionTolerance:num=0.001 orientationTolerance:num=0.01 orientationWeight:num=0.5 damping:num=0.05 "
 "stepSize:num=0.5 maxStep:num=0.1 svdTolerance:num=1e-6 finiteDifferenceStep:num=1e-4 "
 "applyBestOnFailure:flag=true enforceJointLimits:flag=true inverseMethod:name@ik_method=damped_least_squares "
 "transposeGain:num=0"},
{"sensor", 27, Role::Node, "", "",
 "path:text kind:name@sensor_kind parentObject:ref@body position:vec3 orientation:quat",
 "id:id parentGroupId:ref@node parentLink:text width:int=640 height:int=480 updateRate:num=0 verticalFov:num=60 "
 "horizontalFov:num=0 nearPlane:num=0.05 farPlane:num=100 lidarChannels:int=16 lidarSamples:int=1024 "
 "lidarMinRange:num=0.1 lidarMaxRange:num=100 lidarVerticalFov:num=30 segmentation:flag=false calibrationFx:num=0 "
 "calibrationFy:num=0 calibrationCx:num=0 calibrationCy:num=0 noiseMean:num=0 noiseStddev:num=0 noiseSeed:int=0 "
 "enabled:flag=true outputPath:path"},
{"wire", 28, Role::Node, "", "",
 "path:text kind:name@wire_kind bodyA:ref@body bodyB:ref@body length:num",
 "id:id parentGroupId:ref@node localIndexA:int=0 localIndexB:int=0 localPositionA:vec3=0,0,0 "
 "localPositionB:vec3=0,0,0 stiffness:num=1000 damping:num=0 compliance:num=0 visualizationWidth:num=0.01 "
 "enabled:flag=true"},
{"reflection_probe", 29, Role::Node, "", "",
 "path:text position:vec3 radius:num",
 "id:id parentGroupId:ref@node strength:num=1 boxProjection:flag=false boxMin:vec3=-1,-1,-1 boxMax:vec3=1,1,1 "
 "captureOnApply:flag captureCached:flag captureFiltered:flag cubemapSize:int=128 "
 "captureDrawVisualizationObjects:flag=false captureDrawCoordinateFrames:flag captureDrawPointClouds:flag=false "
 "captureShadows:flag=true captureEnvironmentBackground:flag=true captureEnvironmentExposure:num=1 "
 "irradianceResolution:int=32 irradianceSamples:int=64 prefilteredResolution:int=128 prefilteredMipLevels:int=5 "
 "prefilteredSamples:int=64 brdfLutSize:int=128 brdfLutSamples:int=512 enabled:flag=true"},
{"local_fog", 30, Role::Node, "", "",
 "path:text center:vec3 radius:num",
 "id:id parentGroupId:ref@node color:color=1,1,1 density:num=0.5 edgeFade:num=0.3 noiseScale:num=0.25 "
 "noiseStrength:num=0 enabled:flag=true"},
{"projected_decal", 31, Role::Node, "", "",
 "path:text position:vec3 orientation:quat scale:vec3",
 "id:id parentGroupId:ref@node halfExtents:vec3=0.5,0.5,0.5 color:color=1,1,1,1 edgeFade:num=0.05 normalFade:num=0.5 "
 "upperFade:num=0.1 lowerFade:num=0.1 albedoTexture:path emissionTexture:path normalTexture:path ormTexture:path "
 "uvScale:vec2=1,1 uvOffset:vec2=0,0 albedoMix:num=1 emissionEnergy:num=0 normalStrength:num=1 ormStrength:num=1 "
 "distanceFadeEnabled:flag=false distanceFadeBegin:num=12 distanceFadeLength:num=4 enabled:flag=true"},
{"irradiance_volume", 32, Role::Node, "", "",
 "path:text position:vec3 orientation:quat scale:vec3",
 "id:id parentGroupId:ref@node halfExtents:vec3=1,1,1 color:color=1,1,1,1 strength:num=1 edgeFade:num=0.2 "
 "normalBias:num=0.02 enabled:flag=true"},
{"point_cloud", 33, Role::Node, "", "",
 "path:text",
 "id:id parentGroupId:ref@node points:vec3s colors:colors pointSize:num=1 maxRenderedPoints:int "
 "renderedPointStride:int detectable:flag enabled:flag=true"},
{"instanced_visual", 34, Role::Node, "", "",
 "path:text primitive:name@primitive",
 "id:id parentGroupId:ref@node meshPath:path size:vec3=1,1,1 colorA:color=1,1,1,1 colorB:color=1,1,1,1 "
 "instances:xforms colorWeights:nums castShadows:flag=true detectable:flag automaticMeshLod:flag "
 "maxRenderedInstances:int renderedInstanceStride:int projectedLod:flag projectedLodMinRadiusPixels:num "
 "projectedLodMaxStride:int doubleBufferedInstanceUploads:flag sortTransparentInstances:flag grassPatch:flag=false "
 "terrainBinding:ref@terrain terrainFoliageLayer:int densityPreview:flag foliageWindEnabled:flag "
 "grassBladeRootHeight:num grassBladeTipHeight:num grassWindStrength:num grassStiffness:num "
 "grassFlutterWeight:num shadowFoliageLod:flag enabled:flag=true"},
};

// Older object layouts (compat-notes.md): 19 fields end with visible, fixed;
// 17 fields are a visible dynamic body.
const LayoutRow kAltLayouts[] = {
{"object",
 "path:text primitive:name@primitive position:vec3 orientation:quat scale:vec3 radius:num height:num mass:num "
 "contactMaterial:ref@contact material:ref@material visible:flag=true fixed:flag=false"},
{"object",
 "path:text primitive:name@primitive position:vec3 orientation:quat scale:vec3 radius:num height:num mass:num "
 "contactMaterial:ref@contact material:ref@material"},
};

// Enumerations: canonical name first, then its aliases after '='.
const EnumRow kEnums[] = {
{"primitive", "ground=plane box=cube sphere cylinder capsule mesh=static_mesh half_space"},
{"body_mode", "static=fixed kinematic dynamic=movable visual_only=visualonly,visual"},
{"collision_mode", "convex_hull=convexhull,convex,primitive,none,default original_mesh=original,triangle_mesh,trimesh "
                   "convexify=coacd,convex_decomposition"},
{"light_type", "directional=sun point spot area"},
{"wire_kind", "stiff=stiff_wire compliant=soft,compliant_wire custom=custom_wire"},
{"background_mode", "plain_color=plain,color,clear_color,solid hdr=environment,environment_map,cubemap "
                    "rayrai_sky=rayraisky,rayrai,sky,procedural_sky"},
{"color_mode", "fast_linear=linear aces_approx=aces filmic_approx=filmic agx_approx=agx "
               "unreal_preview_approx=unreal,unreal_preview"},
{"render_preset", "fast=low balanced=medium high ultra custom"},
{"weather_preset", "clear hazy overcast fog rain heavy_rain snow storm night_clear night_rain custom"},
{"weather_quality", "low medium high ultra balanced"},
{"alpha_mode", "opaque mask=masked,alpha_scissor hash=alpha_hash blend=transparent"},
{"broadphase", "sap3_axis multi_box_prune=multiboxprune,mbp none=disabled"},
{"solver_mode", "accurate fast ..."},
{"projection", "perspective orthographic"},
{"transform_space", "global local"},
{"terrain_source", "samples png procedural clone"},
{"material_type", "pbr ..."},
{"render_mode", "rgb=color depth segmentation rgb_depth=rgbd ..."},
{"sensor_kind", "rgb=rgb_camera,camera,color depth=depth_camera segmentation rgb_depth=rgbd imu lidar=spinning_lidar force_torque ..."},
{"deformable_kind", "cloth mass_spring fem ..."},
{"deformable_solver", "xpbd pbd"},
{"particle_mode", "skinned surface filled"},
{"contact_model", "hertz linear"},
{"ik_method", "damped_least_squares=dls pseudo_inverse=pinv,pseudoinverse transpose=jacobian_transpose ..."},
};
// clang-format on

const std::size_t kKindCount = sizeof(kKinds) / sizeof(kKinds[0]);
const std::size_t kAltLayoutCount = sizeof(kAltLayouts) / sizeof(kAltLayouts[0]);
const std::size_t kEnumCount = sizeof(kEnums) / sizeof(kEnums[0]);

}  // namespace rscene::table
