// A header of the lower room of cmake/check_rooms.cmake's test fixture.
#pragma once
