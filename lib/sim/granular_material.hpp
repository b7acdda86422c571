// The contact law of one granular record: GranularMaterial, its range
// checks and its stable substep are the scene model's (scene/granular.hpp,
// where the laws are spelled out), so validate and sim judge a record
// alike; the forces are granular_contact.hpp.
#pragma once
#include "scene/granular.hpp"
