#pragma once
// The fog volumes of a scene (output.fog, render/stage/fog_export.h), kept in line by every command that
// changes the diffuse caches or draws from them: run and render, and simulate, so that new caches never
// sit beside fog made from earlier ones.
#include "render/app/scene/scene_args.h"

namespace spume {

// Throws when output.fog asks for fog volumes but no diffuse type is drawn.
void check_fog_request(const SceneSetup& setup);

// Writes, rewrites or removes OUT/<scene>/diffuse_fog/ so that it holds exactly the diffuse caches'
// frames as drawn now (nothing when output.fog is 0); the log says what and why.
void bring_fog_in_line(const SceneSetup& setup);

}  // namespace spume
