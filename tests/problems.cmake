# Tests of problems/: scene reader, writers, the `rodnet` command.
rn_add_test(problems_scene_errors SOURCES unit/problems_scene_errors_test.c
            LIBS rodnet_problems LABELS unit)
