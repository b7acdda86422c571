# fish completion for rscene-to-json
complete -c rscene-to-json -s h -l help -d 'Print help and exit'
complete -c rscene-to-json -l version -d 'Print version and exit'
complete -c rscene-to-json -s o -l output -r -F -d 'Write the JSON to FILE atomically'
complete -c rscene-to-json -s c -l compact -d 'Write the JSON on one line'
complete -c rscene-to-json -s p -l pretty -d 'Indent the JSON'
complete -c rscene-to-json -l schema -d 'Print the JSON Schema of the JSON form'
complete -c rscene-to-json -l stdin-filename -r -F -d 'Name standard input in messages'
complete -c rscene-to-json -k -x -a '(__fish_complete_suffix .rscene)'
