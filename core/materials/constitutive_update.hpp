// Definition of constitutive_update (declared in material.hpp).
#pragma once
