/* A C program over leadscrew's C API (leadscrew.h), run by tests/test_capi.py.
 *
 *   capi_check run SPEC T_END PIECE INPUT VALUE CHANNEL...
 *       a drive from the core spec file SPEC; INPUT held at VALUE ("-" for
 *       none); advanced to T_END in pieces of PIECE seconds; after each piece
 *       one line: the time and the CHANNELs.
 *   capi_check toml TEXT      a drive from TOML text: "ok" or "error CODE: TEXT"
 *   capi_check input SPEC NAME VALUE     set an input: "ok" or "error CODE: TEXT"
 *   capi_check advance SPEC T            advance twice to T: a line per call
 *   capi_check null -                    every function with NULL pointers: a line each
 * Exit code 0 unless the program itself is misused (then 64).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "leadscrew.h"

static int report(int status) {
  if (status == LEADSCREW_OK)
    printf("ok\n");
  else
    printf("error %d: %s\n", status, leadscrew_last_error());
  return 0;
}

static leadscrew_drive* open_spec(const char* path) {
  leadscrew_drive* drive = leadscrew_drive_from_file(path);
  if (!drive) {
    printf("error: %s\n", leadscrew_last_error());
    exit(0);
  }
  return drive;
}

int main(int argc, char** argv) {
  if (argc < 3) return 64;
  const char* mode = argv[1];
  if (strcmp(mode, "null") == 0) {
    double value = 0.0;
    printf("%d\n", leadscrew_drive_from_toml(NULL) == NULL);
    printf("%d\n", leadscrew_drive_from_file(NULL) == NULL);
    report(leadscrew_set_input(NULL, "axial_force", 1.0));
    report(leadscrew_get_input(NULL, "axial_force", &value));
    report(leadscrew_advance(NULL, 1.0));
    report(leadscrew_get_channel(NULL, "u_load", &value));
    report(leadscrew_reset(NULL));
    printf("%d %d %ld %d\n", leadscrew_time(NULL) != leadscrew_time(NULL),
           leadscrew_channel_count(NULL), leadscrew_event_count(NULL),
           leadscrew_channel_name(NULL, 0) == NULL);
    leadscrew_drive_free(NULL);
    return 0;
  }
  if (strcmp(mode, "toml") == 0) {
    leadscrew_drive* drive = leadscrew_drive_from_toml(argv[2]);
    if (drive) {
      leadscrew_drive_free(drive);
      return report(LEADSCREW_OK);
    }
    printf("error: %s\n", leadscrew_last_error());
    return 0;
  }
  leadscrew_drive* drive = open_spec(argv[2]);
  if (strcmp(mode, "run") == 0 && argc >= 7) {
    const double t_end = atof(argv[3]), piece = atof(argv[4]);
    if (strcmp(argv[5], "-") != 0 && leadscrew_set_input(drive, argv[5], atof(argv[6])) != 0) {
      printf("error: %s\n", leadscrew_last_error());
      return 0;
    }
    const long pieces = (long)(t_end / piece + 0.5);
    for (long k = 1; k <= pieces; ++k) {
      const double t = k * piece;
      const int status = leadscrew_advance(drive, t);
      if (status != LEADSCREW_OK) {
        printf("error %d: %s\n", status, leadscrew_last_error());
        break;
      }
      printf("%.17g", leadscrew_time(drive));
      for (int c = 7; c < argc; ++c) {
        double value = 0.0;
        if (leadscrew_get_channel(drive, argv[c], &value) != LEADSCREW_OK) {
          printf("\nerror: %s\n", leadscrew_last_error());
          leadscrew_drive_free(drive);
          return 0;
        }
        printf(" %.17g", value);
      }
      printf("\n");
    }
    printf("events %ld channels %d first %s\n", leadscrew_event_count(drive),
           leadscrew_channel_count(drive), leadscrew_channel_name(drive, 0));
  } else if (strcmp(mode, "input") == 0 && argc >= 5) {
    report(leadscrew_set_input(drive, argv[3], atof(argv[4])));
  } else if (strcmp(mode, "advance") == 0 && argc >= 4) {
    report(leadscrew_advance(drive, atof(argv[3])));
    report(leadscrew_advance(drive, atof(argv[3])));
    report(leadscrew_reset(drive));
    report(leadscrew_advance(drive, 0.001));
  } else {
    leadscrew_drive_free(drive);
    return 64;
  }
  leadscrew_drive_free(drive);
  return 0;
}
