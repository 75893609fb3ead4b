"""``python -m mechnum_course.grading FOLDER``: grade a folder of notebooks (``make grade``)."""

import argparse

from mechnum_course.grading import CELL_LIMIT, NOTEBOOK_LIMIT, grade


def main(argv=None):
    parser = argparse.ArgumentParser(description="Grade a folder of student notebooks.")
    parser.add_argument("folder")
    parser.add_argument("--out", help="where to write the grades (default FOLDER/grading)")
    parser.add_argument("--limit", type=float, default=NOTEBOOK_LIMIT,
                        help="seconds per notebook")
    parser.add_argument("--cell-limit", type=float, default=CELL_LIMIT, help="seconds per cell")
    parser.add_argument("--exercises", help="the exercises graded, e.g. 3.1,3.2")
    args = parser.parse_args(argv)
    numbers = args.exercises.split(",") if args.exercises else None
    print(grade(args.folder, args.out, limit=args.limit, cell_limit=args.cell_limit,
                numbers=numbers), end="")


if __name__ == "__main__":
    main()
