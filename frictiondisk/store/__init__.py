"""What is kept, whatever the task: the append-only journal, atomic files, checked paths,
the DIR layout, CF metadata and the columns every campaign's files share."""
